// libFuzzer entry point: any byte string through the scene parser and validator. A valid scene or a SceneError are
// the only acceptable outcomes; any other exception, a crash or a sanitizer report is a bug.
// Crashes found become regression inputs in tests/scene/fuzz_regressions/ (checked by scene_test).

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "crankcheck/scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const crankcheck::Mechanism m = crankcheck::parseScene(text, "fuzz.toml");
    // A scene that passed validation must describe a mechanism the engines can take.
    if (!(m.crank.radius < m.rod.length) || static_cast<int>(m.machine.crank_angles.size()) != m.machine.cylinders)
      std::abort();
  } catch (const crankcheck::SceneError&) {
  }
  return 0;
}
