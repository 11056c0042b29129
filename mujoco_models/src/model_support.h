#pragma once
// What the library's MuJoCo models share: loading MJCF text into an mjModel (through MuJoCo's virtual file system,
// MuJoCo's error handlers installed once), owning mjModel and mjData, the loops' anchors on the crank, the check on
// the constraint rows. Private to the library (MuJoCo's headers stay in src/).

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck::mujoco_models {

/// An invariant: the constraint rows calcMjcf sized (njmax) held every row MuJoCo made; it drops rows silently
/// otherwise (a warning, which crankcheck does not print). @throws std::logic_error if they did not.
void checkRowsFit(const mjData* d);

/// MJCF text -> a model of its own (the caller may change it): a copy of the same text's compiled model when one of
/// the thread's last few loads had it. The cross-checks build each case's exact model three times (MuJoCo's exact way,
/// and under each soft way's own model), and the compiler is deterministic, so a copy (mj_copyModel) is what a new
/// compile would give, at a small part of its cost.
mjModel* loadModel(const std::string& xml);

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

/// The connect's anchor on the crank: MuJoCo's compiler put it where the big end is at qpos0 (an open loop); the crank
/// pin is where it belongs (mujoco_models/README.md, "Traps met"). Equality j is "loop<j>".
void setCrankPinAnchors(mjModel* model, const Mechanism& m);

}  // namespace crankcheck::mujoco_models
