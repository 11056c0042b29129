#pragma once
// The textbook survey (part survey, parts/survey.cc): the numbered parts, after the scene sections, built on the first
// scene's parts. What the survey's parts share to say so from the tables alone (the report is rendered again from CSV
// by `report merge`): the survey's base (data/survey_base.csv), the scenes the user gave (data/your_engine.csv, given
// == "user": the marks of where the user's engine sits), and the words a part uses when it computes at a speed or with
// a pressure table that no scene gave.

#include <optional>
#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "../your_engine/topic.h"

namespace crankcheck::validation::survey {

/// The base of the survey's figures (data/survey_base.csv, one row): the first scene, and what campaign.cc made of it.
struct SurveyBaseRow {
  std::string scene;      ///< the first scene's stem (Mechanism::name)
  std::string given;      ///< "user": the first scene file given; "built-in": the default campaign's first scene
  int k = 1;              ///< its cylinders
  std::string cycle;      ///< "two-stroke" | "four-stroke"
  double lambda = 0.0;    ///< [-] r / l
  double speed_rpm = 0.0; ///< [rpm] its [engine] speed, the base's
  int single_bank = 1;    ///< 0: it has several banks; the figures use its parts as a standing inline engine
  int centric = 1;        ///< 0: it has pin offsets or balance shafts; the figures use its parts without them
};
extern const Schema<SurveyBaseRow> kSurveyBaseTable;

/// The survey's base, or none when the table is missing (the survey part was not run).
std::optional<SurveyBaseRow> findSurveyBase(const TableSet& tables);

/// The scenes the user gave (given == "user"), in the order given; none in the default campaign.
std::vector<your_engine::SceneFactsRow> listUserScenes(const TableSet& tables);

/// "NAME" or "NAME1, NAME2 and NAME3".
std::string joinNames(const std::vector<std::string>& names);

/// "6000 rpm" or "600, 1500, 3000 and 6000 rpm": speeds as a sentence lists them (shortNumber, 4 digits), ascending,
/// each once.
std::string formatSpeeds(std::vector<double> rpm);

/// What a part says beside a speed no scene gave: "at 6000 rpm, not your scene's speed".
std::string atSurveySpeeds(const std::vector<double>& rpm);

/// What a part says of a pressure table no scene gave.
inline constexpr const char* kExampleGas =
    "the example spark-ignition pressure table (validation/example_gas.h), not your scene's [gas]";
/// The two phrases a test looks for in every part that computes at a speed or with gas that no scene gave.
inline constexpr const char* kNotSceneSpeed = "not your scene's speed";
inline constexpr const char* kNotSceneGas = "not your scene's [gas]";

}  // namespace crankcheck::validation::survey
