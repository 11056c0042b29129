// The report's textbook survey (always run, not numbered, after the scene sections and the scenes): the heading under
// which the numbered parts follow, naming the first scene whose crank, rod and piston they are built on, and what the
// survey's parts share to say where the user's engine sits (survey.h).
#include "survey.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "crankcheck/validation/part.h"
#include "crankcheck/validation/report_format.h"

namespace crankcheck::validation {
namespace survey {

const Schema<SurveyBaseRow> kSurveyBaseTable{
    "survey_base",
    {textField("scene", &SurveyBaseRow::scene), textField("given", &SurveyBaseRow::given),
     countField("k", &SurveyBaseRow::k), textField("cycle", &SurveyBaseRow::cycle),
     numberField("lambda", "-", &SurveyBaseRow::lambda), numberField("speed_rpm", "rpm", &SurveyBaseRow::speed_rpm),
     countField("single_bank", &SurveyBaseRow::single_bank), countField("centric", &SurveyBaseRow::centric)}};

std::optional<SurveyBaseRow> findSurveyBase(const TableSet& tables) {
  const std::vector<SurveyBaseRow>& rows = getRows(tables, kSurveyBaseTable);
  if (rows.empty()) return std::nullopt;
  return rows.front();
}

std::vector<your_engine::SceneFactsRow> listUserScenes(const TableSet& tables) {
  std::vector<your_engine::SceneFactsRow> out;
  for (const your_engine::SceneFactsRow& row : getRows(tables, your_engine::kSceneFactsTable))
    if (row.given == "user") out.push_back(row);
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.scene_index < b.scene_index; });
  return out;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return out;
}

std::string formatSpeeds(std::vector<double> rpm) {
  std::sort(rpm.begin(), rpm.end());
  rpm.erase(std::unique(rpm.begin(), rpm.end()), rpm.end());
  std::vector<std::string> words;
  for (double x : rpm) words.push_back(shortNumber(x, 4));
  return joinNames(words) + " rpm";
}

std::string atSurveySpeeds(const std::vector<double>& rpm) {
  return "at " + formatSpeeds(rpm) + ", " + kNotSceneSpeed;
}

}  // namespace survey

namespace {

using survey::SurveyBaseRow;
using survey::kSurveyBaseTable;

class SurveyPart final : public Part {
 public:
  std::string key() const override { return "survey"; }
  std::string title() const override { return "The textbook survey"; }
  bool always() const override { return true; }
  // The base as campaign.cc made it (PartContext base, first): one row.
  std::vector<Task> tasks(const PartContext& context) const override {
    const Mechanism& first = context.first;
    const SurveyBaseRow row{first.name,
                            context.user_scenes.empty() ? "built-in" : "user",
                            context.base.machine.cylinders,
                            toString(context.base.machine.cycle),
                            calcCrankRatio(context.base),
                            context.base.speed_rpm,
                            isSingleBank(first) ? 1 : 0,
                            hasPinOffsets(first) || !first.balance_shafts.empty() ? 0 : 1};
    return {{"survey_base", false, [row] { return kSurveyBaseTable.tableSet({row}); }}};
  }
  std::vector<const TableSchema*> schemas() const override { return {&kSurveyBaseTable}; }
  std::vector<std::string> figures() const override { return {}; }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    const std::optional<SurveyBaseRow> base = survey::findSurveyBase(tables);
    if (!base) return part;  // not run: left out
    part.heading = "The textbook survey on " + base->scene + "'s parts";
    std::string how;
    if (!base->single_bank || !base->centric) {
      std::vector<std::string> dropped;
      if (!base->single_bank) dropped.push_back("as a standing inline " + std::to_string(base->k) + "-cylinder " +
                                                base->cycle + " engine");
      if (!base->centric) dropped.push_back("centric and without balance shafts");
      how = " (" + survey::joinNames(dropped) + ", as the paper's figures need; its own layout is in its section above)";
    }
    const bool user = !survey::listUserScenes(tables).empty();
    part.blocks.push_back(
        {ReportBlock::kParagraph,
         "What follows is the textbook survey: the error against lambda over 0.01..0.95, k = 1..12, the paper's claims, "
         "the textbook layouts, the integrators and the engines' league. It is built on the crank, rod and piston of " +
             base->scene + (base->given == "user" ? ", the first scene you gave" : ", the default campaign's first scene") +
             how + " (lambda = " + shortNumber(base->lambda, 4) + ", " + shortNumber(base->speed_rpm, 4) +
             " rpm), at the speeds, layouts and pressure tables each part names: where a part computes at a speed or "
             "with a pressure table that no scene gave, its caption says so. " +
             (user ? "Your own engines, exactly as given, are in the sections above; the marks 'your engine' show where "
                     "they sit in the survey's figures and tables."
                   : "The example engines, each exactly as given, are in the sections above.")});
    return part;
  }
};

}  // namespace

namespace parts {
const Part& survey() {
  static const SurveyPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
