#include "crankcheck/validation/campaign.h"


#include <algorithm>
#include <charconv>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "crankcheck/analytic/gravity_torque.h"
#include "crankcheck/analytic/potential_energy.h"
#include "crankcheck/analytic/reactions.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/crosscheck.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/install_paths.h"
#include "crankcheck/validation/parts.h"
#include "crankcheck/validation/extremum.h"
#include "crankcheck/validation/scales.h"
#include "crankcheck/validation/variants.h"


namespace crankcheck::validation {

const Schema<NoteRow> kNotesTable{"notes", {textField("note", &NoteRow::note)}};

const Schema<SceneRow> kScenesTable{
    "scenes",
    {textField("family", &SceneRow::family), textField("scene", &SceneRow::scene),
     countField("cylinders", &SceneRow::cylinders), textField("cycle", &SceneRow::cycle),
     textField("acting", &SceneRow::acting), numberField("gamma_deg", "deg", &SceneRow::gamma_deg),
     numberField("speed_rpm", "rpm", &SceneRow::speed_rpm), numberField("r", "m", &SceneRow::r),
     numberField("l", "m", &SceneRow::l), numberField("lambda", "-", &SceneRow::lambda),
     numberField("m_o", "kg", &SceneRow::m_o), numberField("m_k", "kg", &SceneRow::m_k),
     numberField("z_k", "m", &SceneRow::z_k), numberField("I_o", "kg m^2", &SceneRow::I_o),
     numberField("m_s", "kg", &SceneRow::m_s), numberField("r_s", "m", &SceneRow::r_s),
     numberField("m_p", "kg", &SceneRow::m_p), numberField("r_p", "m", &SceneRow::r_p),
     numberField("g", "m/s^2", &SceneRow::g), optionalField("I_w", "kg m^2", &SceneRow::I_w)}};


namespace {

// ------------------------------------------------------------------------------------------------------------
// Scenes

Mechanism makeScene(const std::string& name, int k, Cycle cycle, double gamma_deg, double rpm) {
  Mechanism m;
  m.name = name;
  m.machine.cylinders = k;
  m.machine.cycle = cycle;
  m.machine.crank_angles = calcPhaseAngles(k, cycle, Acting::kSingle);
  m.machine.cylinder_angle = radiansFromDegrees(gamma_deg);
  m.speed_rpm = rpm;
  m.machine.speed = rpm * (M_PI / 30.0);
  // A passenger-car cylinder (the example scene scenes/single_cylinder.toml).
  m.crank = {0.043, 1.2, 0.02, 0.8, 0.035};
  m.rod = {0.145, 0.55, 0.105, 0.0072};
  m.piston.mass = 0.35;
  m.flywheel_inertia = 0.15;
  return m;
}

}  // namespace

std::vector<Mechanism> buildDefaultScenes() {
  std::vector<Mechanism> scenes;
  for (double gamma : {90.0, 0.0, 180.0, -90.0})
    scenes.push_back(makeScene("single_cylinder_four_" + gammaTag(gamma), 1, Cycle::kFourStroke, gamma, 3000.0));
  for (int k : {2, 3, 4, 6, 8, 12})
    for (Cycle cycle : {Cycle::kTwoStroke, Cycle::kFourStroke}) {
      const bool two = cycle == Cycle::kTwoStroke;
      scenes.push_back(makeScene("inline" + std::to_string(k) + (two ? "_two_" : "_four_") + gammaTag(90.0), k, cycle,
                                 90.0, two ? 3000.0 : 6000.0));
    }
  for (double gamma : {0.0, 180.0, -90.0})
    scenes.push_back(makeScene("inline4_four_" + gammaTag(gamma), 4, Cycle::kFourStroke, gamma, 6000.0));
  // Marine scale: a slow two-stroke crosshead diesel (scenes/inline6_two_stroke_marine.toml).
  Mechanism marine = makeScene("marine_inline6_two_gamma90", 6, Cycle::kTwoStroke, 90.0, 105.0);
  marine.crank = {1.2, 9000.0, 0.6, 6000.0, 0.9};
  marine.rod = {3.0, 12000.0, 1.9, 55000.0};
  marine.piston.mass = 14000.0;
  marine.flywheel_inertia = 9.0e5;
  scenes.push_back(marine);
  // Small-engine scale: a 50 cm^3 single-cylinder two-stroke.
  Mechanism small = makeScene("small_engine_single_two_gamma90", 1, Cycle::kTwoStroke, 90.0, 9000.0);
  small.crank = {0.02, 0.15, 0.008, 0.1, 0.014};
  small.rod = {0.075, 0.035, 0.05, 1.2e-4};
  small.piston.mass = 0.06;
  small.flywheel_inertia = 0.004;
  scenes.push_back(small);
  return scenes;
}

std::string familyOf(const Mechanism& m) {
  const std::string& n = m.name;
  if (n.rfind("single_cylinder", 0) == 0) return "single cylinder (gamma 90/0/180/-90)";
  if (n.rfind("inline4_four_gamma", 0) == 0 && n != "inline4_four_gamma90") return "inline 4 four-stroke (gamma 0/180/-90)";
  if (n.rfind("inline", 0) == 0) return n.find("_two_") != std::string::npos ? "inline two-stroke (k = 2..12)" : "inline four-stroke (k = 2..12)";
  if (n.rfind("marine", 0) == 0) return "marine scale (inline 6 two-stroke)";
  if (n.rfind("small_engine", 0) == 0) return "small-engine scale (50 cm^3)";
  return n;
}

std::vector<Mechanism> loadExampleScenes() {
  const std::filesystem::path dir = findScenesDir();
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<Mechanism> scenes;
  for (const auto& file : files) scenes.push_back(loadSceneFile(file));
  return scenes;
}

std::vector<Task> buildCampaign(const CampaignOptions& options) {
  const bool quick = options.quick;
  const std::vector<Mechanism> scenes = options.scenes.empty() ? buildDefaultScenes() : options.scenes;
  // (family of cases, scene): the built-in scenes are grouped into families, user scenes are their own family.
  std::vector<std::pair<std::string, Mechanism>> families;
  for (const Mechanism& m : scenes) families.emplace_back(options.scenes.empty() ? familyOf(m) : m.name, m);
  // The paper's figures are about one bank of cylinders: a layout's base scene gives them its parts as
  // a standing inline engine of the same k and cycle, and the report says so.
  const Mechanism& first = scenes.front();
  Mechanism base = isSingleBank(first) ? first : withGamma(withCylinders(first, first.machine.cylinders, first.machine.cycle), 90.0);
  // The paper's figures are about centric cylinders: an offset base scene gives them its parts centric (the offset part
  // and the cross-checks show the offset engine itself).
  const bool offset_base = hasPinOffsets(base) || !base.balance_shafts.empty();
  base.machine.pin_offsets.clear();
  base.balance_shafts.clear();

  std::vector<Task> tasks;
  std::vector<NoteRow> notes;
  // The paper's parts, by their numbers in the registry: from the error against lambda to the integrators.
  const std::string paper_parts = std::to_string(findPart("error_vs_lambda").number()) + "-" +
                                  std::to_string(findPart("integrator_pareto").number());
  if (!isSingleBank(first))
    notes.push_back({"The first scene, " + first.name + ", has cylinders in more than one bank; the figures of parts " +
                     paper_parts + ", written for the paper's inline engine, use its parts as a standing inline engine "
                     "of the same cylinder count and cycle. Its own layout is cross-checked in the summary."});
  if (offset_base)
    notes.push_back({"The first scene, " + first.name + ", has pin offsets or balance shafts; the figures of parts " +
                     paper_parts + ", written for the paper's centric engine without shafts, use its parts without "
                     "them. Its own engine is cross-checked in the summary, and part " +
                     std::to_string(findPart("offset").number()) + " shows what an offset changes."});
  // The user's scenes, or the example scenes (scenes/*.toml) in the default campaign: the parts on given scenes.
  std::vector<Mechanism> pin_scenes = options.scenes;
  if (pin_scenes.empty()) pin_scenes = loadExampleScenes();
  // The free-run parts need the base scene's flywheel; without one they are left out, and the report says so:
  // crankcheck invents no inertia on the user's behalf.
  if (!base.flywheel_inertia)
    notes.push_back({"Parts " + std::to_string(findPart("delta_vs_k").number()) + " and " +
                     std::to_string(findPart("integrator_pareto").number()) + " (the free run) are left out: the base "
                     "scene " + base.name + " has no [flywheel] inertia and crankcheck does not assume one. Give the "
                     "first scene a [flywheel] table to get them."});
  for (const SatOut& s : options.sat_out)
    notes.push_back({"Engine " + s.engine + " sat out of this campaign: it cannot build scene " + s.scene + " (" +
                     escapeText(formatOneLine(s.reason)) + "). Every table, verdict and figure is of the other engines."});
  if (!options.parts.empty()) {
    std::string asked;
    for (const std::string& key : options.parts) asked += (asked.empty() ? "" : ", ") + key;
    notes.push_back({"Only the report parts " + asked + " were run (validate --parts); the cross-checks and the "
                          "verdict are whole."});
  }
  // Every registered part's tasks (parts.h), in report order; a part with nothing to show for these scenes says why.
  const PartContext context{base, first, pin_scenes, options.scenes, families, quick, options.work_limit};
  std::vector<const Part*> selected;
  for (const Part* part : listParts())
    if (part->always() || options.parts.empty() ||
        std::find(options.parts.begin(), options.parts.end(), part->key()) != options.parts.end())
      selected.push_back(part);  // validate --parts: only those asked for, and the report's core
  for (const Part* part : selected) part->checkWork(context);  // before any work: a refusal, not hours
  for (const Part* part : selected)
    if (const std::string why = part->findOmission(context); !why.empty())
      notes.push_back({"Part " + std::to_string(part->number()) + " (" + part->key() + ") is left out: " + why});
  if (!notes.empty()) tasks.push_back({"notes", false, [notes] { return kNotesTable.tableSet(notes); }});
  for (const Part* part : selected)
    for (Task& task : part->tasks(context)) tasks.push_back(std::move(task));
  // The longest tasks first, so that the jobs finish together (the order changes no table: they are sorted): the
  // flywheel sizings (one task per Simbody run), the offset sweep, then the cross-checks and the gate's sweep, largest
  // k first, then the rest in the order listed (Task::cost).
  std::stable_sort(tasks.begin(), tasks.end(), [](const Task& a, const Task& b) { return a.cost > b.cost; });
  return tasks;
}

}  // namespace crankcheck::validation
