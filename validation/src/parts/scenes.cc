// The report's scenes (always run, not numbered): every value of every cross-checked scene, and the campaign's notes
// (what it left out, and why).
#include <string>
#include <vector>

#include "crankcheck/scene/mechanism.h"
#include "crankcheck/validation/campaign_scenes.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_format.h"
#include "crankcheck/validation/table.h"
#include "crankcheck/validation/task.h"
#include "crankcheck/validation/part.h"

namespace crankcheck::validation {
namespace {

std::vector<SceneRow> listSceneRows(const std::vector<std::pair<std::string, Mechanism>>& families) {
  std::vector<SceneRow> rows;
  for (const auto& [family, m] : families)
    rows.push_back({family, m.name, m.machine.cylinders, toString(m.machine.cycle), toString(m.machine.acting),
                    degreesFromRadians(m.machine.cylinder_angle), m.speed_rpm, m.crank.radius, m.rod.length,
                    calcCrankRatio(m), m.piston.mass, m.rod.mass, m.rod.com_from_wrist_pin,
                    m.rod.inertia_about_wrist_pin, m.crank.mass, m.crank.com_radius, m.crank.counterweight_mass,
                    m.crank.counterweight_radius, m.machine.gravity, m.flywheel_inertia});
  return rows;
}

class ScenesPart final : public Part {
 public:
  std::string key() const override { return "scenes"; }
  std::string title() const override { return "Scenes"; }
  bool always() const override { return true; }
  std::vector<Task> tasks(const PartContext& context) const override {
    return {{"scenes", false, [families = context.families] { return kScenesTable.tableSet(listSceneRows(families)); }}};
  }
  std::vector<const TableSchema*> schemas() const override { return {&kScenesTable}; }
  std::vector<std::string> figures() const override { return {}; }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count(kScenesTable.name())) return part;  // not run: left out
    part.heading = heading();
    part.blocks.push_back({ReportBlock::kParagraph,
                           "Each scene is cross-checked at its own lambda and, in the full campaign, with the rod "
                           "lengthened or shortened to lambda = 0.1, 0.2, 0.3, 0.4, 0.6, 0.9. The first scene is the "
                           "base of the figures. SI units."});
    ReportBlock table{ReportBlock::kTable, "", {"scene", "family", "k", "cycle", "gamma [deg]", "speed [rpm]", "r [m]",
                                                "l [m]", "lambda [-]", "m_o [kg]", "m_k [kg]", "z_k [m]",
                                                "I_o [kg m^2]", "m_s [kg]", "r_s [m]", "m_p [kg]", "r_p [m]",
                                                "g [m/s^2]", "I_w [kg m^2]"}};
    auto number = [](double x) { return shortNumber(x, 4); };
    for (const SceneRow& s : getRows(tables, kScenesTable))
      table.rows.push_back({s.scene, s.family, std::to_string(s.cylinders), s.cycle, number(s.gamma_deg),
                            number(s.speed_rpm), number(s.r), number(s.l), number(s.lambda), number(s.m_o),
                            number(s.m_k), number(s.z_k), number(s.I_o), number(s.m_s), number(s.r_s), number(s.m_p),
                            number(s.r_p), number(s.g), s.I_w ? number(*s.I_w) : std::string()});
    part.blocks.push_back(table);
    part.blocks.push_back({ReportBlock::kParagraph,
                           "Every value used is shown. Where a scene file leaves a key out, crankcheck uses the default "
                           "of docs/SCENE-FORMAT.md: g = 9.80665 m/s^2, single acting, no counterweight (m_p = 0), "
                           "throw angles from eqs (8)-(11). I_w is the flywheel inertia, empty where the scene has none."});
    for (const NoteRow& note : getRows(tables, kNotesTable)) part.blocks.push_back({ReportBlock::kParagraph, note.note});
    return part;
  }
};

}  // namespace

namespace parts {
const Part& scenes() {
  static const ScenesPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
