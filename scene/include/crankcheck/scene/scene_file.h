#pragma once
/// @file
/// Scene files: TOML (parsed with toml++) describing one mechanism. The format is documented in
/// docs/SCENE-FORMAT.md; every key is checked, unknown keys are errors.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "crankcheck/scene/mechanism.h"

namespace crankcheck {

/// The scene format this crankcheck reads. A scene may say `format_version = 1` at its top; a larger number is
/// refused with a message asking for a newer crankcheck (no key of a newer format is guessed at).
inline constexpr int kSceneFormatVersion = 1;

/// A user error in a scene: the message names the file, the key and the rule that was broken.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads and validates a scene file. Besides the tables, the top level may hold `format_version` (1, or 1.0),
/// `name` and `description` (strings for people and editors; a scene is named by its file's stem everywhere in
/// crankcheck's output, Mechanism::name). The JSON Schema docs/scene.schema.json describes the same format.
/// @throws SceneError with "FILE: KEY: rule" if the file cannot be read, is not TOML, has an unknown or
///         missing key, a value of the wrong type, or breaks a physical rule (see validateMechanism).
Mechanism loadSceneFile(const std::filesystem::path& path);

/// Parses scene text; `source_name` is used in messages (normally the file path).
/// @throws SceneError as loadSceneFile.
Mechanism parseScene(std::string_view toml_text, const std::string& source_name);

/// Checks the physical rules a mechanism must obey, each limit with its own unit and reason (docs/SCENE-FORMAT.md,
/// "Limits"): finite values; lengths, masses, inertias, speed, gravity and angles within their limits;
/// lambda < 1; 0 <= z_k <= l; I_o >= m_k z_k^2; crank angle count = k.
/// @throws SceneError with "SOURCE: KEY: rule" for the first rule broken.
void validateMechanism(const Mechanism& m, const std::string& source_name);

}  // namespace crankcheck
