#pragma once
/// @file
/// How every command reads its scene files.

#include <string>

#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/errors.h"

namespace crankcheck::app {

/// loadSceneFile, with a bad scene turned into the user's error (exit status 2) with the same "FILE: KEY: rule".
inline Mechanism loadScene(const std::string& path) {
  try {
    return loadSceneFile(path);
  } catch (const SceneError& e) {
    throw UsageError(e.what());
  }
}

/// The line the commands that keep the shaft rigid add to their table when the scene has a [crankshaft] (the elastic
/// train only `crankcheck torsion` reads); empty without one.
inline std::string describeRigidShaft(const Mechanism& m) {
  return m.crankshaft ? "(the [crankshaft] is not used: this command treats the shaft as rigid; see crankcheck torsion)\n"
                      : "";
}

}  // namespace crankcheck::app
