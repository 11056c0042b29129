// What the library's MuJoCo models share (model_support.h).
#include "model_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/scene/scene_file.h"

namespace crankcheck::mujoco_models {
namespace {

constexpr const char* kFileName = "crankcheck.xml";

// MuJoCo reports errors through a handler that must not return; the default one prints and calls exit(1), and
// writes MUJOCO_LOG.TXT into the working directory. crankcheck checks every input MuJoCo would refuse before it
// builds a model, so an error here is MuJoCo's own failure: one line and exit status 3 (internal failure), no log
// file in the user's folder. Warnings (e.g. a non-finite acceleration, after which MuJoCo resets its data) are not
// printed (they would corrupt --format json on stdout): every result is checked for finiteness instead.
[[noreturn]] void onMujocoError(const char* message) {
  std::fprintf(stderr, "crankcheck: MuJoCo failed: %s\n", message);
  std::fflush(stderr);
  std::_Exit(3);
}
void onMujocoWarning(const char*) {}
void installHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = onMujocoError;
    mju_user_warning = onMujocoWarning;
  });
}

/// MJCF text -> mjModel through MuJoCo's virtual file system (2.2.2 has no mj_loadXMLString). One file system per
/// thread, kept: mjVFS holds 2000 file names of 1000 bytes, and zeroing a new one (mj_defaultVFS) was a quarter of
/// a one-cylinder model's build (0.41 ms). The file is removed again after each load, whatever happens.
mjModel* compileModel(const std::string& xml) {
  thread_local const std::unique_ptr<mjVFS> vfs = [] {
    auto fresh = std::make_unique<mjVFS>();  // large: on the heap
    mj_defaultVFS(fresh.get());
    return fresh;
  }();
  if (mj_makeEmptyFileVFS(vfs.get(), kFileName, static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("MuJoCo: could not make the in-memory model file");
  struct RemoveFile {
    mjVFS* vfs;
    ~RemoveFile() { mj_deleteFileVFS(vfs, kFileName); }
  } remove_file{vfs.get()};
  const int index = mj_findFileVFS(vfs.get(), kFileName);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[1024] = "";
  mjModel* model = mj_loadXML(kFileName, vfs.get(), error, sizeof error);
  if (!model) {
    std::string text = error;  // MuJoCo's message spans lines: one line here, as every message of crankcheck
    for (char& c : text)
      if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    throw std::runtime_error("MuJoCo could not compile the model: " + text);
  }
  return model;
}

}  // namespace

void checkRowsFit(const mjData* d) {
  if (d->warning[mjWARN_CNSTRFULL].number > 0)
    throw std::logic_error("MuJoCo: the constraint rows outgrew the model's njmax (calcMjcf's <size>)");
}

mjModel* loadModel(const std::string& xml) {
  installHandlers();
  constexpr size_t kKept = 4;
  struct Compiled {
    std::string xml;
    std::unique_ptr<mjModel, void (*)(mjModel*)> model;
  };
  thread_local std::vector<Compiled> kept;
  auto found = std::find_if(kept.begin(), kept.end(), [&](const Compiled& c) { return c.xml == xml; });
  if (found == kept.end()) {
    if (kept.size() == kKept) kept.erase(kept.begin());
    kept.push_back({xml, {compileModel(xml), mj_deleteModel}});
    found = kept.end() - 1;
  }
  mjModel* copy = mj_copyModel(nullptr, found->model.get());
  if (!copy) throw std::runtime_error("MuJoCo: could not copy a compiled model");
  return copy;
}

void setCrankPinAnchors(mjModel* model, const Mechanism& m) {
  for (int j = 0; j < m.machine.cylinders; ++j) {
    const int equality = mj_name2id(model, mjOBJ_EQUALITY, ("loop" + std::to_string(j)).c_str());
    const double beta = getThrowAngle(m, j);
    double* data = model->eq_data + mjNEQDATA * equality;
    data[3] = m.crank.radius * std::cos(beta);
    data[4] = m.crank.radius * std::sin(beta);
    data[5] = getAxialPosition(m, j);
  }
}

}  // namespace crankcheck::mujoco_models
