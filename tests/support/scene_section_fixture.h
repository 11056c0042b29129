#pragma once
// What the tests of the scene sections' topics (tests/validation/your_engine/) share: a topic by its title, its tables
// on one scene as the campaign computes them (every task, with the scene's facts row the describe reads), the text of
// its blocks.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../validation/src/your_engine/topic.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/table.h"

namespace crankcheck::testing {

/// The registered topic titled `title`. @throws std::logic_error if there is none.
inline const validation::your_engine::SceneTopic& findTopic(const std::string& title) {
  for (const validation::your_engine::SceneTopic* topic : validation::your_engine::listTopics())
    if (topic->title() == title) return *topic;
  throw std::logic_error("no scene-section topic \"" + title + "\"");
}

/// The tables of `topic` on m: every task's, appended, and m's facts row (as a scene the user gave).
inline validation::TableSet runTopic(const validation::your_engine::SceneTopic& topic, const Mechanism& m,
                                     bool quick = false) {
  validation::TableSet tables;
  for (const validation::Task& task : topic.tasks(m, quick)) validation::appendTables(tables, task.run());
  validation::addRows(tables, validation::your_engine::kSceneFactsTable, {validation::your_engine::calcSceneFacts(m, 0, true)});
  return tables;
}

/// Every block's text, table header and fields, one block a line: what a test searches for a sentence or a cell.
inline std::string joinText(const std::vector<validation::ReportBlock>& blocks) {
  std::string s;
  for (const validation::ReportBlock& b : blocks) {
    s += b.text + "\n";
    for (const std::string& h : b.header) s += h + " | ";
    for (const auto& row : b.rows)
      for (const std::string& f : row) s += f + " | ";
  }
  return s;
}

/// The example scene scenes/STEM.toml.
inline Mechanism loadExample(const std::string& stem) {
  return loadSceneFile(std::filesystem::path(CRANKCHECK_SCENES_DIR) / (stem + ".toml"));
}

}  // namespace crankcheck::testing
