#include "torsion_command.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "crankcheck/validation/commands/torsion.h"
#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/work_limit.h"
#include "flag_checks.h"
#include "help_format.h"
#include "json_output.h"
#include "scene_input.h"

namespace crankcheck::app {
namespace {

constexpr int kMaxSpeeds = 1000;
/// [rpm] The largest speed a flag takes: the scene file's limit on [engine].speed_rpm (docs/SCENE-FORMAT.md, "Limits").
constexpr double kMaxSpeedRpm = 1e6;

// A speed [rpm] as typed for `flag`: a whole finite number in (0, 1e6], else UsageError naming the flag.
double parseSpeed(const std::string& text, const std::string& flag) {
  double rpm = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf%c", &rpm, &tail) != 1)
    throw UsageError(flag + ": expected a speed in rpm, got '" + escapeText(text) + "'");
  if (!(std::isfinite(rpm) && rpm > 0 && rpm <= kMaxSpeedRpm))
    throw UsageError(flag + ": must be > 0 and at most 1e6 rpm, the scene file's limit (got " + formatShortest(rpm) + ")");
  return rpm;
}

// FROM:TO:STEP [rpm] -> the speeds FROM, FROM + STEP, ... up to TO (within a millionth of a step), each in (0, 1e6].
// STEP at least 1e-6 x TO; the count is checked before any speed is made, and the speeds made are checked again: at
// most kMaxSpeeds, each above the last and at most 1e6 rpm (rounding of FROM + i STEP).
std::vector<double> parseSpeeds(const std::string& text) {
  double from = 0, to = 0, step = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf:%lf:%lf%c", &from, &to, &step, &tail) != 3)
    throw UsageError("--speeds: expected FROM:TO:STEP in rpm (e.g. 1000:6000:250), got '" + escapeText(text) + "'");
  if (!(std::isfinite(from) && std::isfinite(to) && std::isfinite(step) && from > 0 && to >= from && step > 0))
    throw UsageError("--speeds: needs 0 < FROM <= TO and STEP > 0 (got '" + escapeText(text) + "')");
  if (to > kMaxSpeedRpm)
    throw UsageError("--speeds: TO must be at most 1e6 rpm, the scene file's limit (got " + formatShortest(to) + ")");
  // A step below a millionth of TO resolves no speed (FROM = TO included: such a STEP is a typing error, not a sweep).
  if (step < 1e-6 * to)
    throw UsageError("--speeds: STEP must be at least 1e-6 x TO (got " + formatShortest(step) + " for TO " +
                     formatShortest(to) + ")");
  const double count = std::floor((to - from) / step + 1e-6) + 1;
  if (!(count <= kMaxSpeeds))
    throw UsageError("--speeds: " +
                     (count < 1e15 ? std::to_string(static_cast<long long>(count)) : formatShortest(count)) +
                     " speeds; at most " + std::to_string(kMaxSpeeds));
  std::vector<double> speeds;
  for (int i = 0; i < static_cast<int>(count); ++i) {
    const double rpm = from + i * step;
    if (rpm > kMaxSpeedRpm || (!speeds.empty() && !(rpm > speeds.back())))
      throw UsageError("--speeds: STEP " + formatShortest(step) + " does not give " +
                       formatShortest(count) + " distinct speeds of at most 1e6 rpm from " + formatShortest(from));
    speeds.push_back(rpm);
  }
  return speeds;
}

}  // namespace

void addTorsionOptions(CLI::App& command, TorsionOptions& options) {
  command.add_option("scene", options.scene_path, "Scene file (TOML) with a [crankshaft] table")->required();
  command.footer(
      "Domain: results are computed only for a shaft that twists at most 0.1 rad a section (a crankshaft, not a chain "
      "of loose masses). A scene whose throws' mean torque twists a section beyond that is refused before any work "
      "(status 2, naming [crankshaft].stiffness[i]). The work is estimated before it starts (probes of the train's "
      "equations at up to 8 of the speeds and of each engine's step) and refused past --work-limit (status 2). A "
      "speed at which Holzer's linear twist exceeds the domain, a steady state past its own work limit (1e8 "
      "evaluations of the train's equations, about a minute; an engine's train: 3e5 Simbody or 4e6 MuJoCo steps) or "
      "one that does not converge is refused with one line, status 1, nothing printed. Very "
      "stiff shafts (8 x the highest natural frequency's order above 65536 harmonics: the example four from about 3e4 "
      "x its stiffness) take the stiff limit, K^-1 T in closed form plus its corrections, where its bound is within 1 % "
      "of the twist (from about 3e5 x), else the explicit route (docs/torsion.md).");
  // As text, parsed in runTorsion: CLI11 takes an empty value ('') for a number as not given.
  auto* speed = command.add_option_function<std::string>(
      "--speed", [&options](const std::string& text) { options.speed = text; },
      "One speed [rpm], in (0, 1e6] (default: the scene's speed_rpm)");
  auto* speeds = command.add_option_function<std::string>(
      "--speeds", [&options](const std::string& text) { options.speeds = text; },
      "A sweep FROM:TO:STEP [rpm], e.g. 1000:6000:250 (at most 1000 speeds, each in (0, 1e6])");
  speed->excludes(speeds);
  std::vector<std::string> names;
  std::string help = "The exact steady states to show (comma-separated; the analytic one is always computed):";
  for (const Engine& e : validation::listEngines())
    if (e.simulate_crank_train) {
      names.push_back(e.name);
      help += " " + e.name + " (" + e.crank_train_method + ")" + (e.crank_train_gated ? "" : " [soft: not gated]") + ";";
    }
  command.add_option("--engine", options.engines, help)
      ->delimiter(',')
      ->check(CLI::IsMember(names))
      ->capture_default_str();
  command.add_option(validation::kWorkLimitFlag, options.work_limit,
                     "The longest work to start [s]: the speeds' steady states and the engines' trains are estimated "
                     "before they start (probes of the train's equations and of each engine's step) and refused past it")
      ->check(FiniteRange(1.0, 1e7))
      ->capture_default_str();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember({"table", "json"}))
      ->capture_default_str();
}

std::string runTorsion(const TorsionOptions& options) {
  // Everything that can be refused is refused before the first steady state is computed.
  std::vector<double> speeds;
  if (options.speeds) speeds = parseSpeeds(*options.speeds);
  if (options.speed) speeds = {parseSpeed(*options.speed, "--speed")};
  const Mechanism scene = loadScene(options.scene_path);
  if (speeds.empty() && scene.crankshaft) {  // without [crankshaft], calcTorsion says so first
    if (!(scene.speed_rpm > 0))
      throw UsageError(options.scene_path + ": [engine].speed_rpm: must be > 0 for torsion (the flywheel's driven "
                                            "speed), or give --speed or --speeds");
    speeds = {scene.speed_rpm};
  }
  // The engines' own trains (every named engine but the closed forms, whose exact steady state is always shown).
  std::vector<const Engine*> trains;
  for (size_t i = 0; i < options.engines.size(); ++i) {
    const std::string& name = options.engines[i];
    // A name given twice is refused, as validate --parts refuses a key given twice: which was meant is not known.
    if (std::find(options.engines.begin(), options.engines.begin() + static_cast<long>(i), name) !=
        options.engines.begin() + static_cast<long>(i))
      throw UsageError("--engine: " + name + " is given twice");
    const Engine& e = validation::findEngine(name);
    if (!e.closed_form) trains.push_back(&e);
  }
  const bool progress = (speeds.size() > 1 || !trains.empty()) && ::isatty(STDERR_FILENO);
  validation::TorsionResult torsion;
  try {
    torsion = validation::calcTorsion(scene, speeds, trains, options.work_limit, [&](size_t s) {
      if (progress) std::fprintf(stderr, "\r\033[Ktorsion: speed %zu of %zu (%g rpm)", s + 1, speeds.size(), speeds[s]);
    });
  } catch (const std::invalid_argument& e) {
    throw UsageError(options.scene_path + ": " + e.what());
  } catch (const UsageError& e) {  // the work estimated past --work-limit
    throw UsageError(options.scene_path + ": " + e.what());
  } catch (const validation::TorsionSpeedError& e) {
    throw UncomputableError(options.scene_path + " at " + formatShortest(e.rpm) + " rpm: " + e.what());
  } catch (const UncomputableError& e) {
    throw UncomputableError(options.scene_path + ": " + e.what());
  }
  if (progress) std::fprintf(stderr, "\r\033[K");
  const analytic::TorsionModes& modes = torsion.modes;
  const std::vector<analytic::ThrowInertia>& inertias = torsion.inertias;
  const std::vector<validation::CriticalSpeed>& critical = torsion.critical;
  const std::vector<validation::TorsionSpeed>& results = torsion.speeds;
  const double lo = torsion.range_lo, hi = torsion.range_hi;
  const int bodies = static_cast<int>(modes.inertias.size());
  const bool has_front = scene.crankshaft->front_inertia > 0.0;

  auto sectionName = [&](int i) {
    // Section i joins body i and body i + 1: front-0, 0-1, ..., (k-1)-flywheel.
    auto body = [&](int b) {
      if (b >= bodies) return std::string("flywheel");
      if (has_front && b == 0) return std::string("front");
      return "throw " + std::to_string(b - (has_front ? 1 : 0));
    };
    return body(i) + " / " + body(i + 1);
  };

  if (options.format == "json") {
    nlohmann::ordered_json doc;
    doc["scene"] = options.scene_path;
    nlohmann::ordered_json throws = nlohmann::ordered_json::array();
    for (size_t j = 0; j < inertias.size(); ++j)
      throws.push_back({{"throw", j}, {"exact_inertia", inertias[j].exact},
                        {"half_reciprocating", inertias[j].half_reciprocating},
                        {"second_order", inertias[j].second_order}});
    doc["throw_inertias"] = throws;
    nlohmann::ordered_json freq = nlohmann::ordered_json::array();
    for (int i = 0; i < modes.frequencies.size(); ++i)
      freq.push_back({{"mode", i + 1}, {"omega", modes.frequencies(i)}, {"hz", modes.frequencies(i) / (2 * M_PI)}});
    doc["natural_frequencies"] = freq;
    nlohmann::ordered_json crit = nlohmann::ordered_json::array();
    for (const validation::CriticalSpeed& c : critical) crit.push_back({{"mode", c.mode}, {"order", c.order}, {"speed_rpm", c.rpm}});
    doc["critical_speeds"] = crit;
    nlohmann::ordered_json at = nlohmann::ordered_json::array();
    for (const validation::TorsionSpeed& r : results) {
      nlohmann::ordered_json sections = nlohmann::ordered_json::array();
      for (int i = 0; i < bodies; ++i) {
        sections.push_back({{"section", sectionName(i)},
                            {"holzer", r.holzer.peak_to_peak[static_cast<size_t>(i)]},
                            {"holzer_order24", r.holzer.peak_to_peak_order24[static_cast<size_t>(i)]},
                            {"exact", r.exact.peak_to_peak[static_cast<size_t>(i)]},
                            {"difference", r.exact.peak_to_peak[static_cast<size_t>(i)] /
                                                   r.holzer.peak_to_peak[static_cast<size_t>(i)] - 1.0}});
        for (size_t e = 0; e < trains.size(); ++e) {
          sections.back()[trains[e]->name] = r.trains[e][static_cast<size_t>(i)];
          sections.back()[trains[e]->name + "_difference"] =
              r.trains[e][static_cast<size_t>(i)] / r.holzer.peak_to_peak[static_cast<size_t>(i)] - 1.0;
        }
      }
      at.push_back({{"speed_rpm", r.rpm},
                    {"peak_to_peak_twist", sections},
                    {"holzer_harmonics", r.holzer.orders},
                    {"exact_newton_iterations", r.exact.newton_iterations},
                    {"exact_error_bound", r.exact.error_bound}});
      for (size_t e = 0; e < trains.size(); ++e) at.back()[trains[e]->name + "_cycles"] = r.train_cycles[e];
    }
    doc["speeds"] = at;
    return dumpJson(doc);
  }

  std::string out;
  char line[512];
  out += "torsion of " + showPath(options.scene_path) + ": " + std::to_string(bodies) +
         " bodies clamped at the flywheel (driven at the speed)\n";
  out += "\nthrow inertia for Holzer [kg m^2]: exact (J_t + mean of J over a turn), the textbook's shortcuts\n";
  std::snprintf(line, sizeof line, "%-8s %18s %22s %22s\n", "throw", "exact", "half reciprocating", "second order");
  out += line;
  for (size_t j = 0; j < inertias.size(); ++j) {
    std::snprintf(line, sizeof line, "%-8zu %18.12g %14.9g (%+.2e) %14.9g (%+.2e)\n", j, inertias[j].exact,
                  inertias[j].half_reciprocating, inertias[j].half_reciprocating / inertias[j].exact - 1,
                  inertias[j].second_order, inertias[j].second_order / inertias[j].exact - 1);
    out += line;
  }
  out += "\nnatural frequencies (Holzer, clamped at the flywheel)\n";
  for (int i = 0; i < modes.frequencies.size(); ++i) {
    std::snprintf(line, sizeof line, "mode %-3d %18.12g rad/s %16.10g Hz\n", i + 1, modes.frequencies(i),
                  modes.frequencies(i) / (2 * M_PI));
    out += line;
  }
  std::snprintf(line, sizeof line, "\ncritical speeds of orders <= 24 from %g to %g rpm (rpm = 30 w / (pi n))\n", lo, hi);
  out += line;
  if (critical.empty()) out += "none\n";
  for (const validation::CriticalSpeed& c : critical) {
    std::snprintf(line, sizeof line, "mode %-3d order %-5g %14.8g rpm\n", c.mode, c.order, c.rpm);
    out += line;
  }
  // Within 100 columns: each engine's train in a table of its own below the analytic one. A difference to Holzer is
  // shown only where the exact value stands above its error bound (else "< bound": the digits are not the twist's).
  for (const validation::TorsionSpeed& r : results) {
    std::snprintf(line, sizeof line,
                  "\npeak-to-peak twist at %g rpm [rad]: Holzer (every order, %d harmonics; cut at order 24),\n"
                  "exact steady state (error bound %.1e rad)\n",
                  r.rpm, r.holzer.orders, r.exact.error_bound);
    out += line;
    std::snprintf(line, sizeof line, "%-20s %17s %17s %17s %15s\n", "section", "holzer", "holzer n<=24",
                  "exact (analytic)", "exact/holzer-1");
    out += line;
    auto difference = [&](double value, size_t k) {
      if (!(value > r.exact.error_bound)) return std::string("< bound");
      char text[32];
      std::snprintf(text, sizeof text, "%+.4e", value / r.holzer.peak_to_peak[k] - 1.0);
      return std::string(text);
    };
    for (int i = 0; i < bodies; ++i) {
      const size_t k = static_cast<size_t>(i);
      std::snprintf(line, sizeof line, "%-20s %17.9e %17.9e %17.9e %15s\n", sectionName(i).c_str(),
                    r.holzer.peak_to_peak[k], r.holzer.peak_to_peak_order24[k], r.exact.peak_to_peak[k],
                    difference(r.exact.peak_to_peak[k], k).c_str());
      out += line;
    }
    for (size_t e = 0; e < trains.size(); ++e) {
      std::snprintf(line, sizeof line, "%-20s %16s %17s\n", "section", trains[e]->name.c_str(),
                    (trains[e]->name + "/holzer-1").c_str());
      out += line;
      for (int i = 0; i < bodies; ++i) {
        const size_t k = static_cast<size_t>(i);
        std::snprintf(line, sizeof line, "%-20s %16.9e %+17.4e\n", sectionName(i).c_str(), r.trains[e][k],
                      r.trains[e][k] / r.holzer.peak_to_peak[k] - 1.0);
        out += line;
      }
    }
  }
  return wrapText(out, kHelpWidth);
}

}  // namespace crankcheck::app
