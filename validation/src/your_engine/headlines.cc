// The terminal's line per user scene (scene_sections.h): its most telling numbers, from the sections' tables.
#include <algorithm>
#include <cmath>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/scene_sections.h"
#include "topic.h"

namespace crankcheck::validation {

std::string formatSceneHeadlines(const TableSet& tables) {
  using namespace your_engine;
  std::vector<SceneFactsRow> facts = getRows(tables, kSceneFactsTable);
  std::sort(facts.begin(), facts.end(), [](const SceneFactsRow& a, const SceneFactsRow& b) { return a.scene_index < b.scene_index; });
  const std::string& closed_forms = getClosedFormEngine().name;  // the exact closed forms, the rows' own reference
  std::string out;
  for (const SceneFactsRow& f : facts) {
    if (f.given != "user") continue;
    std::vector<std::string> clauses;
    // Norton's two-term a_p: the formula engineers use most, judged on this scene against the exact closed forms.
    for (const FitnessRow& r : getRows(tables, kFitnessTable))
      if (r.scene == f.scene && r.reference == closed_forms && r.quantity == "a_p" && r.formula.rfind("Norton", 0) == 0)
        clauses.push_back("Norton's a_p " + formatFitness(r.max_error_rel, r.resolved != 0) + " of " + r.scale);
    // The paper's question: does gravity matter for this engine at its speed.
    for (const GravityRow& r : getRows(tables, kGravityTable))
      if (r.scene == f.scene && r.engine == closed_forms && (std::isfinite(r.ratio) || !r.resolved))
        clauses.push_back(r.resolved ? "gravity " + shortNumber(r.ratio, 2) + " of the inertia torque"
                                     : std::string("gravity's torque cancels (rounding)"));
    if (clauses.empty()) continue;
    // Within 100 columns, as every line crankcheck prints: a clause that does not fit goes on a line of its own.
    std::string line = "  " + f.scene + ":";
    for (size_t i = 0; i < clauses.size(); ++i) {
      const std::string clause = " " + clauses[i] + (i + 1 < clauses.size() ? ";" : "");
      if (line.size() + clause.size() > 100 && line.size() > 4) {
        out += line + "\n";
        line = "   ";
      }
      line += clause;
    }
    out += line + "\n";
  }
  return out;
}

}  // namespace crankcheck::validation
