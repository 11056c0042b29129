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

}  // namespace crankcheck::app
