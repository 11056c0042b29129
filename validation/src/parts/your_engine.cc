// The report's scene sections (always run, not numbered, after the verdict): for each scene the user gives (the
// example scenes in the default campaign) a section "NAME: your engine", computed on the scene exactly as given. The
// section's topics are the files of validation/src/your_engine/ (topic.h), listed in topics.cc.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "crankcheck/validation/part.h"
#include "crankcheck/validation/report_format.h"
#include "../your_engine/topic.h"

namespace crankcheck::validation {
namespace {

using your_engine::SceneFactsRow;
using your_engine::kSceneFactsTable;

// "with its [gas] table, 1 balance shaft, a flywheel; no [crankshaft]": what the scene has and lacks.
std::string describeHas(const SceneFactsRow& f) {
  std::vector<std::string> has, lacks;
  (f.gas ? has : lacks).push_back("[gas]");
  (f.flywheel ? has : lacks).push_back("[flywheel]");
  (f.crankshaft ? has : lacks).push_back("[crankshaft]");
  if (f.balance_shafts > 0) has.push_back(std::to_string(f.balance_shafts) + " [[balance_shaft]]");
  if (f.pin_offsets) has.push_back("pin offsets up to " + shortNumber(f.max_pin_offset * 1e3, 3) + " mm");
  auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (size_t i = 0; i < v.size(); ++i) s += (i == 0 ? "" : ", ") + v[i];
    return s;
  };
  std::string out;
  if (!has.empty()) out += "with " + join(has);
  if (!lacks.empty()) out += std::string(out.empty() ? "" : "; ") + "no " + join(lacks);
  return out;
}

class YourEnginePart final : public Part {
 public:
  std::string key() const override { return "your_engine"; }
  std::string title() const override { return "Your engine"; }
  bool always() const override { return true; }
  // The user's scenes, or the example scenes in the default campaign: the facts of each, then every topic's tasks.
  std::vector<Task> tasks(const PartContext& context) const override {
    const bool user = !context.user_scenes.empty();
    const std::vector<Mechanism>& scenes = user ? context.user_scenes : context.scenes;
    std::vector<SceneFactsRow> facts;
    for (size_t i = 0; i < scenes.size(); ++i) facts.push_back(your_engine::calcSceneFacts(scenes[i], static_cast<int>(i), user));
    std::vector<Task> out = {{"your_engine facts", false, [facts] { return kSceneFactsTable.tableSet(facts); }}};
    for (const Mechanism& m : scenes)
      for (const your_engine::SceneTopic* topic : your_engine::listTopics())
        for (Task& task : topic->tasks(m, context.quick)) out.push_back(std::move(task));
    return out;
  }
  void derive(TableSet& tables) const override {
    for (const your_engine::SceneTopic* topic : your_engine::listTopics()) topic->derive(tables);
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    std::vector<SceneFactsRow> facts = getRows(tables, kSceneFactsTable);
    if (facts.empty()) return part;  // not run: left out
    std::sort(facts.begin(), facts.end(), [](const SceneFactsRow& a, const SceneFactsRow& b) { return a.scene_index < b.scene_index; });
    const bool user = facts.front().given == "user";
    part.heading = user ? (facts.size() == 1 ? "Your engine" : "Your engines") : "The example engines";
    part.blocks.push_back(
        {ReportBlock::kParagraph,
         std::string(user ? "A section for each scene you gave" : "A section for each example scene (scenes/*.toml)") +
             ", computed on the scene exactly as given: its layout, its speed, its gas table, pin offsets, balance "
             "shafts, flywheel and crankshaft where it has them, in the closed forms and in every engine. Errors are "
             "relative to the scale named beside each; the tables are in data/your_engine*.csv, one row per scene and "
             "value, each naming its scene by its file's stem. The textbook survey (the numbered parts) follows."});
    for (const SceneFactsRow& f : facts) {
      part.blocks.push_back({ReportBlock::kHeading, f.scene + (user ? ": your engine" : ": example engine"), {}, {}, {}, 3,
                             "your-engine-" + f.scene});
      part.blocks.push_back({ReportBlock::kParagraph, "Layout: " + f.layout + "; " + shortNumber(f.speed_rpm, 4) +
                                                          " rpm; lambda = r / l = " + shortNumber(f.lambda, 4) + "; " +
                                                          describeHas(f) + "."});
      for (const your_engine::SceneTopic* topic : your_engine::listTopics()) {
        std::vector<ReportBlock> blocks = topic->describe(tables, f.scene);
        if (blocks.empty()) continue;
        part.blocks.push_back({ReportBlock::kHeading, topic->title(), {}, {}, {}, 4});
        for (ReportBlock& b : blocks) part.blocks.push_back(std::move(b));
      }
    }
    return part;
  }
  std::vector<const TableSchema*> schemas() const override {
    std::vector<const TableSchema*> out = {&kSceneFactsTable};
    for (const your_engine::SceneTopic* topic : your_engine::listTopics())
      for (const TableSchema* schema : topic->schemas())
        if (std::find(out.begin(), out.end(), schema) == out.end()) out.push_back(schema);
    return out;
  }
  std::vector<std::string> figures() const override {
    std::vector<std::string> out;
    for (const your_engine::SceneTopic* topic : your_engine::listTopics())
      for (const std::string& figure : topic->figures()) out.push_back(figure);
    return out;
  }
  std::vector<ReportedMaximum> maxima() const override {
    std::vector<ReportedMaximum> out;
    for (const your_engine::SceneTopic* topic : your_engine::listTopics())
      for (const ReportedMaximum& m : topic->maxima()) out.push_back(m);
    return out;
  }
};

}  // namespace

namespace parts {
const Part& yourEngine() {
  static const YourEnginePart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
