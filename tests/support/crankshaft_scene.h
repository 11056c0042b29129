#pragma once
/// @file
/// An example scene with a `[crankshaft]` table of the test's own (tests of the torsion analysis).

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "crankcheck/scene/scene_file.h"

namespace crankcheck::testing {

/// The scene file `path` with its own `[crankshaft]` table (the example scenes end with it, when they have one)
/// replaced by `crankshaft_table` (the table's keys, without its header).
inline Mechanism loadSceneWithCrankshaft(const std::filesystem::path& path, const std::string& crankshaft_table) {
  std::ifstream in(path);
  std::ostringstream file;
  file << in.rdbuf();
  std::string text = file.str();
  const size_t own = text.find("\n[crankshaft]");
  if (own != std::string::npos) text.resize(own + 1);
  return parseScene(text + "\n[crankshaft]\n" + crankshaft_table, path.filename().string());
}

}  // namespace crankcheck::testing
