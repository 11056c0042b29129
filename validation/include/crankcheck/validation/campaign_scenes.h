#pragma once
/// @file
/// The campaign's scenes: the built-in families, the example scenes, and how the report lists each (data/scenes.csv).
/// Below the parts and the campaign, which both read them.

#include <optional>
#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// One scene of the campaign as the report lists it: every value used (SI; gamma in degrees, speed in rpm).
struct SceneRow {
  std::string family, scene;
  int cylinders = 1;
  std::string cycle, acting;
  double gamma_deg = 0, speed_rpm = 0, r = 0, l = 0, lambda = 0, m_o = 0, m_k = 0, z_k = 0, I_o = 0, m_s = 0, r_s = 0,
         m_p = 0, r_p = 0, g = 0;
  std::optional<double> I_w;  ///< empty: the scene has no flywheel
};

/// data/scenes.csv.
extern const Schema<SceneRow> kScenesTable;

/// The built-in scenes: a single cylinder (gamma 90, 0, 180, -90), inline 2, 3, 4, 6, 8, 12 in both strokes,
/// an inline four at gamma 0, 180, -90, a marine-size and a small-engine scale.
std::vector<Mechanism> buildDefaultScenes();

/// The example scenes, scenes/*.toml (the folder findScenesDir finds: install_paths.h), sorted by
/// file name: the scenes of report part pin_load_polar in the default campaign. @throws SceneError if one
/// does not load.
std::vector<Mechanism> loadExampleScenes();

}  // namespace crankcheck::validation
