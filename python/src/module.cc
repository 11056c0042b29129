// The Python module crankcheck._crankcheck (pybind11): scenes, every engine of validation::listEngines() over NumPy
// arrays of crank angles, balance, the free run, `crankcheck grade` of a Python function, and the closed forms of
// fourier_series.h and kinematics.h as plain functions of lambda. python/crankcheck/__init__.py is the public face.
//
// Names, units (SI, radians) and conventions are the CLI's (docs/eval.md, docs/CONVENTIONS.md); a
// scene that the CLI refuses is refused here as crankcheck.SceneError with the CLI's message (without the CLI's
// "crankcheck: " prefix). The engines run with the GIL released; each call builds its own engine model, so calls from
// several Python threads run in parallel (an EngineModel is used by one thread only: solver/engine.h).

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "batch_evaluation.h"
#include "crankcheck/analytic/batch.h"
#include "crankcheck/analytic/fourier_series.h"
#include "crankcheck/analytic/kinematics.h"
#include "crankcheck/analytic/motion.h"
#include "crankcheck/analytic/shaking.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/scene/scene_writer.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/commands/motion.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/evaluation_json.h"
#include "crankcheck/validation/free_run_grade.h"
#include "crankcheck/validation/work_limit.h"
#include "crankcheck/validation/grade.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/report.h"
#include "crankcheck/validation/runner.h"
#include "crankcheck/validation/scales.h"
#include "grade_bridge.h"

namespace py = pybind11;

namespace crankcheck::python {
namespace {

using Angles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A scene as Python holds it: the mechanism and the name messages use for it (the file path, as the CLI's).
struct Scene {
  Mechanism m;
  std::string source;
};
using ScenePtr = std::shared_ptr<Scene>;

// JSON (nlohmann) to Python objects through Python's own json module: the same numbers the CLI prints.
py::object toPython(const nlohmann::ordered_json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

py::array_t<double> toArray(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// ---- Angles: the buffer of a C-contiguous float64 array is used as it is (no copy); anything else (a float, a list,
// another dtype, a strided view) is converted once by NumPy.
/// `x` as a C-contiguous float64 array: `name` is the argument in messages ("phi", "degrees", a result's key) and
/// `unit` its unit. Throws TypeError for None and for what is not real numbers.
Angles asAngles(const py::handle& x, const std::string& name = "phi", const std::string& unit = "rad") {
  // Real numbers only: NumPy would read None as NaN, drop a complex value's imaginary part with a warning, and read
  // the string "30" as 30 rad. numpy.asarray returns a C-contiguous float64 array itself, and raises NumPy's own error
  // for what is not numbers.
  const bool angle = unit == "rad" || unit == "deg";
  if (x.is_none())
    throw py::type_error(name + ": " + (angle ? "a crank angle [" + unit + "]" : "a number [" + unit + "]") +
                         " or an array of them, not None");
  const py::module_ numpy = py::module_::import("numpy");
  const py::object given = numpy.attr("asarray")(x);
  const std::string kind = py::str(given.attr("dtype").attr("kind"));
  if (kind != "f" && kind != "i" && kind != "u")
    throw py::type_error(name + ": real numbers [" + unit + "] (got an array of dtype " +
                         std::string(py::str(given.attr("dtype"))) +
                         (kind == "c" ? (angle ? ": a complex angle has no crank position)" : ": not a real value)")
                                      : ")"));
  const py::object a = numpy.attr("asarray")(given, py::arg("dtype") = "float64", py::arg("order") = "C");
  return Angles::ensure(a);
}

std::span<const double> spanOf(const Angles& a) { return {a.data(), static_cast<size_t>(a.size())}; }

// ---- Outputs: one NumPy array per quantity, laid out [component][cylinder][angle...] in memory (what the batch
// kernels write, BatchOutput) and returned as the view of shape phi.shape + (k,) + (components,), so that no value is
// copied. The views are Fortran-ordered (each component contiguous).
struct Output {
  const QuantityInfo* info;
  py::array buffer;  // float64, C-contiguous, [component][cylinder][angle...]
};

size_t prefixDims(const QuantityInfo& q) { return (q.components > 1 ? 1 : 0) + (q.per_cylinder ? 1 : 0); }

Output allocate(const QuantityInfo& q, int k, const std::vector<py::ssize_t>& angle_shape) {
  std::vector<py::ssize_t> shape;
  if (q.components > 1) shape.push_back(q.components);
  if (q.per_cylinder) shape.push_back(k);
  shape.insert(shape.end(), angle_shape.begin(), angle_shape.end());
  return {&q, py::array_t<double>(shape)};
}

// The memory of an array an earlier evaluate returned (out=): view()'s transpose undone, checked to be what allocate
// makes, so that the kernels write into it again (no new memory: no page to fault in and zero).
Output reuse(const QuantityInfo& q, int k, const std::vector<py::ssize_t>& angle_shape, const py::dict& out) {
  const std::string where = std::string("out[\"") + q.name + "\"]";
  const std::string rule = " (out must be a result of evaluate with the same scene, phi's shape and quantities)";
  if (!out.contains(q.name)) throw py::value_error(where + ": missing" + rule);
  const py::object v = out[q.name];
  if (!py::isinstance<py::array>(v)) throw py::value_error(where + ": not a NumPy array" + rule);
  const size_t prefix = prefixDims(q), d = angle_shape.size();
  const std::string layout_rule = ": not the float64 array of this shape and layout evaluate returns";
  // Another rank (phi of another rank than the call that made it) is another shape: the same message as any, before
  // the transpose below would fail with NumPy's own ("axes don't match array").
  if (v.attr("ndim").cast<size_t>() != prefix + d) throw py::value_error(where + layout_rule + rule);
  py::list inverse;  // buffer axis b is view axis (b < prefix: d + prefix - 1 - b; else b - prefix)
  for (size_t b = 0; b < prefix + d; ++b) inverse.append(b < prefix ? d + prefix - 1 - b : b - prefix);
  const py::array buffer = v.attr("transpose")(py::tuple(inverse));
  std::vector<py::ssize_t> shape;
  if (q.components > 1) shape.push_back(q.components);
  if (q.per_cylinder) shape.push_back(k);
  shape.insert(shape.end(), angle_shape.begin(), angle_shape.end());
  const bool layout = buffer.dtype().equal(py::dtype::of<double>()) && (buffer.flags() & py::array::c_style) &&
                      std::vector<py::ssize_t>(buffer.shape(), buffer.shape() + buffer.ndim()) == shape;
  if (!layout) throw py::value_error(where + layout_rule + rule);
  if (!buffer.writeable()) throw py::value_error(where + ": read-only");
  return {&q, buffer};
}

py::object view(const Output& o, size_t angle_dims) {
  const size_t prefix = prefixDims(*o.info);
  py::list axes;
  for (size_t a = 0; a < angle_dims; ++a) axes.append(prefix + a);
  for (size_t a = prefix; a-- > 0;) axes.append(a);  // cylinder, then component
  py::object v = o.buffer.attr("transpose")(py::tuple(axes));
  if (v.attr("ndim").cast<int>() == 0) return v[py::tuple()];  // a float angle gives NumPy scalars
  return v;
}

std::vector<std::string> defaultQuantities(const Mechanism& m) {
  std::vector<std::string> names;
  for (const QuantityInfo& q : listQuantities())
    if (isDefined(m, q.name)) names.push_back(q.name);
  return names;
}

std::string joinQuantityNames() {
  std::string all;
  for (const QuantityInfo& q : listQuantities()) all += std::string(all.empty() ? "" : ", ") + q.name;
  return all;
}

// The CLI's refusal of a scene an engine cannot build: "SOURCE: --engine NAME: KEY: rule".
std::unique_ptr<EngineModel> buildModel(const Scene& s, const Engine& engine) {
  try {
    return engine.build(s.m);
  } catch (const std::invalid_argument& e) {
    throw SceneError(s.source + ": --engine " + engine.name + ": " + e.what());
  } catch (const std::exception& e) {
    throw std::runtime_error(s.source + ": --engine " + engine.name + ": " + engine.library + " failed: " + e.what());
  }
}

const Engine& engineNamed(const std::string& name) {
  try {
    return validation::findEngine(name);
  } catch (const std::invalid_argument&) {
    // findEngine's words, the name quoted with its control bytes escaped (a NUL would cut the message).
    throw py::value_error("engine: no engine " + quoteText(name) + "; the engines are " + validation::joinEngineNames(", "));
  }
}

py::dict evaluate(const ScenePtr& scene, const py::handle& phi_in, const std::string& engine_name,
                  const std::optional<std::vector<std::string>>& quantities, const std::optional<py::dict>& reused) {
  const Mechanism& m = scene->m;
  const Engine& engine = engineNamed(engine_name);
  const Angles phi = asAngles(phi_in);
  std::vector<py::ssize_t> angle_shape(phi.shape(), phi.shape() + phi.ndim());
  // Which quantities: all that the scene defines (U_star, Q_star without a flywheel and a speed: None, as eval's null;
  // gas_force without [gas]: absent, as in eval), or the caller's list.
  const std::vector<std::string> names = quantities ? *quantities : defaultQuantities(m);
  std::set<std::string> seen;
  for (const std::string& name : names) {
    if (!findQuantity(name))
      throw py::value_error("quantities: " + quoteText(name) + " is not a quantity of eval (one of " + joinQuantityNames() + ")");
    if (!isDefined(m, name))
      throw py::value_error("quantities: " + name + " is not defined for " + scene->source +
                            (findQuantity(name)->star ? " (it needs [flywheel].inertia and speed_rpm > 0)" : " (it has no [gas] table)"));
    if (!seen.insert(name).second) throw py::value_error("quantities: " + name + " is given twice");
  }
  if (reused && angle_shape.empty()) throw py::value_error("out: needs phi with at least one dimension (arrays to write into)");
  std::vector<Output> outputs;
  BatchOutput out;
  for (const QuantityInfo& q : listQuantities())
    if (seen.count(q.name)) {
      outputs.push_back(reused ? reuse(q, m.machine.cylinders, angle_shape, *reused)
                               : allocate(q, m.machine.cylinders, angle_shape));
      out.at(q.name) = static_cast<double*>(outputs.back().buffer.mutable_data());
    }
  std::span<const double> angles = spanOf(phi);
  // Angles beyond 4 pi in magnitude are reduced to rounding (reduceCrankAngle) into a copy; the usual angles are
  // read in place, from phi's own buffer.
  std::vector<double> reduced;
  if (std::any_of(angles.begin(), angles.end(), [](double a) { return std::fabs(a) > 4.0 * M_PI; })) {
    reduced.assign(angles.begin(), angles.end());
    for (double& a : reduced) a = reduceCrankAngle(a);
    angles = reduced;
  }
  {
    py::gil_scoped_release release;
    try {
      if (&engine == &validation::getClosedFormEngine()) {  // the closed forms' own batch kernels
        evaluateAnalyticBatch(m, angles, out);
      } else {
        const std::unique_ptr<EngineModel> model = buildModel(*scene, engine);
        evaluateModel(m, engine, *model, angles, out);
      }
    } catch (const std::invalid_argument& e) {
      throw py::value_error(e.what());  // an angle that is not finite
    }
  }
  if (reused) return *reused;  // written in place
  py::dict result;
  size_t next = 0;
  for (const QuantityInfo& q : listQuantities()) {
    if (next < outputs.size() && outputs[next].info == &q) {
      result[q.name] = view(outputs[next++], angle_shape.size());
    } else if (!quantities && q.star) {
      result[q.name] = py::none();  // eval: null without a flywheel or at rest
    }
  }
  return result;
}

// ---- balance: the CLI's JSON (app/balance_command.cc) from the same validation::calcBalance, without its words
// ("reason": vanishes_by_symmetry holds what they say).
py::object balance(const ScenePtr& scene, int order) {
  if (order < 1 || order > 64) throw py::value_error("order: " + std::to_string(order) + " not in [1 - 64]");
  const Mechanism& m = scene->m;
  std::vector<validation::BalanceRow> rows;
  std::vector<validation::SatOut> sat_out;  // as the CLI's: a reference engine that cannot build the scene sits out
  {
    py::gil_scoped_release release;
    try {
      rows = validation::calcBalance(m, order, 0, &sat_out);
    } catch (const std::invalid_argument& e) {
      throw SceneError(scene->source + ": " + e.what());
    }
  }
  nlohmann::ordered_json doc;
  doc["scene"] = validation::sceneToJson(m);
  doc["order"] = order;
  doc["samples"] = std::max(64, 4 * order);
  doc["resolution"] = validation::balanceResolutionToJson(validation::calcBalanceResolution(m));
  doc["harmonics"] = validation::balanceToJson(rows, hasAxialPositions(m));
  doc["sat_out"] = validation::satOutToJson(sat_out);
  return toPython(doc);
}

// ---- motion: the CLI's JSON from the library's calcMotion (validation/commands/motion.h), optionally with each engine's run.
py::object motion(const ScenePtr& scene, const std::string& integrator, double accuracy,
                  const std::string& mujoco_integrator, double mujoco_step, double stepped_step,
                  const std::string& stepped_settings, bool series) {
  const Mechanism& m = scene->m;
  const std::string& source = scene->source;
  // The CLI's checks of its flags, by the parameters' names, from the registry (validation/commands/motion.h).
  auto checkMember = [](const char* parameter, const std::vector<std::string>& set, const std::string& x) {
    if (std::find(set.begin(), set.end(), x) != set.end()) return;
    std::string names;
    for (const std::string& name : set) names += (names.empty() ? "" : ", ") + name;
    throw py::value_error(std::string(parameter) + ": " + escapeText(x) + " not in {" + names + "}");
  };
  checkMember("integrator", validation::listIntegrators(true), integrator);
  checkMember("mujoco_integrator", validation::listIntegrators(false), mujoco_integrator);
  checkMember("stepped_settings", validation::listSteppedSettings(), stepped_settings);
  if (!(accuracy >= 1e-14 && accuracy <= 1e-1)) throw py::value_error("accuracy: value not in range 1e-14 to 0.1");
  if (!(mujoco_step >= 1e-6 && mujoco_step <= 1e-1)) throw py::value_error("mujoco_step: value not in range 1e-06 to 0.1");
  if (!(stepped_step >= 1e-5 && stepped_step <= 1e-1)) throw py::value_error("stepped_step: value not in range 1e-05 to 0.1");
  // Each pair goes to the engines that offer its integrator (Engine::integrators), as the CLI's flags.
  validation::FreeRunChoices choices = validation::getDefaultFreeRunSettings();
  validation::chooseIntegrator(choices, integrator, accuracy);
  validation::chooseIntegrator(choices, mujoco_integrator, mujoco_step);
  validation::chooseSteppedRun(choices, stepped_settings, stepped_step);
  std::vector<validation::MotionRun> runs;
  std::vector<validation::SatOut> sat_out;  // as the CLI's: an engine that cannot build the scene sits out
  {
    py::gil_scoped_release release;
    try {
      runs = validation::calcMotion(m, choices, &sat_out);
    } catch (const std::invalid_argument& e) {
      throw SceneError(source + ": " + e.what());
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(source + ": " + e.what());
    }
  }
  nlohmann::ordered_json doc;
  for (const validation::MotionRun& r : runs) {
    doc[r.engine] = validation::motionRunToJson(r);
  }
  doc["sat_out"] = validation::satOutToJson(sat_out);
  py::object result = toPython(doc);
  if (series)
    for (const validation::MotionRun& r : runs) {
      if (r.integrator.empty() || !r.not_measured.empty()) continue;  // the energy integral has no steps
      // The run with gravity, step by step: time [s], phi [rad] (unwrapped), phi_dot [rad/s], energy [J].
      py::dict s;
      s["time"] = toArray(r.with_gravity.trajectory.time);
      s["phi"] = toArray(r.with_gravity.trajectory.phi);
      s["phi_dot"] = toArray(r.with_gravity.trajectory.omega);
      s["energy"] = toArray(r.with_gravity.energy);
      result[py::str(r.engine)]["series"] = s;
    }
  return result;
}

// ---- grade: the user's function answers `crankcheck grade`'s requests (grade_bridge.h).

std::string formatShape(const std::vector<py::ssize_t>& shape) {
  std::string text = "(";
  for (size_t d = 0; d < shape.size(); ++d) text += (d ? ", " : "") + std::to_string(shape[d]);
  return text + (shape.size() == 1 ? ",)" : ")");
}

// The function's answer for case c as protocol 1's response line: {"results": [{"phi_deg", "U", ..., "cylinders":
// [...]}, ...]}. Called with the GIL held.
std::string toResponse(const validation::GradeCase& c, const py::handle& answer) {
  const std::string where = "crankcheck.grade: case " + c.id + ": ";
  if (!py::isinstance<py::dict>(answer))
    throw py::type_error(where + "the function must return a dict of eval's quantities (as Scene.evaluate does), not " +
                         std::string(py::str(answer.get_type().attr("__name__"))));
  const size_t n = c.phi_deg.size();
  const int k = c.mechanism.machine.cylinders;
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  for (size_t i = 0; i < n; ++i) results.push_back({{"phi_deg", c.phi_deg[i]}});
  for (const auto& [key_handle, value] : py::reinterpret_borrow<py::dict>(answer)) {
    const std::string key = py::str(key_handle);
    const QuantityInfo* q = findQuantity(key);
    if (!q) throw py::value_error(where + quoteText(key) + " is not a quantity of eval (one of " + joinQuantityNames() + ")");
    if (value.is_none() || q->star) continue;  // not provided; the dimensionless NAME_star are not graded
    const Angles a = asAngles(value, where + "result[\"" + key + "\"]", q->quantity->unit);
    std::vector<py::ssize_t> expected = {static_cast<py::ssize_t>(n)};
    if (q->per_cylinder) expected.push_back(k);
    if (q->components > 1) expected.push_back(q->components);
    const std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
    if (shape != expected)
      throw py::value_error(where + "result[\"" + key + "\"] has shape " + formatShape(shape) + ", expected " +
                            formatShape(expected) + " (angles" + (q->per_cylinder ? ", cylinders" : "") +
                            (q->components > 1 ? ", components" : "") + ")");
    const double* data = a.data();
    const int cyls = q->per_cylinder ? k : 1;
    for (size_t i = 0; i < n; ++i)
      for (int j = 0; j < cyls; ++j) {
        nlohmann::ordered_json value_json;
        for (int comp = 0; comp < q->components; ++comp) {
          const double x = data[(i * static_cast<size_t>(cyls) + static_cast<size_t>(j)) * static_cast<size_t>(q->components) +
                                static_cast<size_t>(comp)];
          nlohmann::ordered_json number = x;
          if (!std::isfinite(x)) {
            // shaking_moment X, Y without axial positions are not defined (eval: null; Scene.evaluate: NaN): not graded.
            if (!isComponentDefined(*q->quantity, comp, c.mechanism)) {
              number = nullptr;
            } else {
              throw py::value_error(where + "result[\"" + key + "\"][" + std::to_string(i) + (q->per_cylinder ? ", " + std::to_string(j) : "") +
                                    (q->components > 1 ? ", " + std::to_string(comp) : "") + "] = " + std::to_string(x) +
                                    " is not a finite number (leave a quantity out, or None, to not provide it)");
            }
          }
          if (q->components > 1) value_json.push_back(number);
          else value_json = number;
        }
        if (q->per_cylinder) {
          nlohmann::ordered_json& cylinders = results[i]["cylinders"];
          if (cylinders.is_null())
            for (int jj = 0; jj < k; ++jj) cylinders.push_back(nlohmann::ordered_json::object());
          cylinders[static_cast<size_t>(j)][key] = value_json;
        } else {
          results[i][key] = value_json;
        }
      }
  }
  return nlohmann::ordered_json{{"results", results}}.dump();
}

// A path argument as C++ reads it: os.fsdecode's str (a str, bytes or os.PathLike). A NUL byte cannot be in a file's
// name, and C would read the path only up to it (naming another file): the callers refuse it.
std::string pathArgument(const py::handle& path) { return py::str(py::module_::import("os").attr("fsdecode")(path)); }

bool hasNul(const std::string& text) { return text.find('\0') != std::string::npos; }

// A scene file read as the CLI reads it; a path with a NUL is refused as a missing file is ("FILE: file: rule"), the
// path quoted with the NUL escaped.
ScenePtr loadScene(const py::handle& path_object) {
  const std::string path = pathArgument(path_object);
  if (hasNul(path)) throw SceneError(quotePath(path) + ": file: cannot be read (a path with a NUL byte: no file has that name)");
  return std::make_shared<Scene>(Scene{loadSceneFile(path), path});
}

// A grade under way (grade_bridge.h). crankcheck.grade (__init__.py) answers its requests in the calling thread: next
// and answer until finished, then result; stop at any other ending (an exception, a timeout, Ctrl-C).
struct GradeRun {
  std::unique_ptr<InProcessGrade> bridge;
  std::unique_ptr<validation::OutputFolder> folder;
  validation::GradeReportInfo info;
  std::string relay, program_name;
  std::optional<std::string> out_dir;
  double timeout_seconds = 0.0;
  int jobs = 1;
  bool quick = true;
  std::chrono::steady_clock::time_point start;
};

std::unique_ptr<GradeRun> startGrade(const std::optional<std::vector<py::object>>& scenes, bool quick, int jobs,
                                     double timeout_seconds, const std::optional<py::object>& out, const py::object& relay,
                                     const std::string& program_name) {
  if (!(timeout_seconds >= 0.001 && timeout_seconds <= 1e6)) throw py::value_error("timeout: value not in range 0.001 to 1e+06");
  if (jobs < 0 || jobs > 256) throw py::value_error("jobs: value not in range 1 to 256");
  auto run = std::make_unique<GradeRun>();
  run->relay = pathArgument(relay);
  if (hasNul(run->relay)) throw py::value_error("relay: " + quotePath(run->relay) + ": a path with a NUL byte");
  if (out) {
    run->out_dir = pathArgument(*out);
    if (hasNul(*run->out_dir))
      throw py::value_error("out: " + quotePath(*run->out_dir) + ": a path with a NUL byte (no folder has that name)");
  }
  run->program_name = escapeText(program_name);  // the function's name, in messages and the report
  run->timeout_seconds = timeout_seconds;
  run->quick = quick;
  // Everything that can be checked is checked before the first case, as the CLI does: the scenes (each engine must
  // build each), the output folder, gnuplot.
  std::vector<Mechanism> mechanisms;
  std::set<std::string> names;
  if (scenes)
    for (const py::object& item : *scenes) {
      const ScenePtr s = py::isinstance<Scene>(item) ? item.cast<ScenePtr>() : loadScene(item);
      mechanisms.push_back(s->m);
      if (!names.insert(s->m.name).second) throw SceneError(s->source + ": a scene named " + s->m.name + " is given twice");
      try {  // Python's grade holds every engine to every scene: one that would sit out is a refusal here
        const std::vector<validation::SatOut> sat_out = validation::findSatOut({s->m}, {s->source});
        if (!sat_out.empty())
          throw SceneError(s->source + ": --engine " + sat_out.front().engine + ": " + sat_out.front().reason);
      } catch (const UsageError& e) {
        throw SceneError(e.what());
      }
    }
  if (run->out_dir) {
    run->folder = std::make_unique<validation::OutputFolder>(*run->out_dir, "out");
    run->info.gnuplot_version = validation::checkGnuplot();
  }
  GradeSettings settings;
  settings.relay = run->relay;
  run->jobs = jobs > 0 ? jobs : validation::getDefaultJobs();
  settings.jobs = run->jobs;
  run->start = std::chrono::steady_clock::now();
  py::gil_scoped_release release;
  std::vector<validation::GradeCase> cases = validation::buildGradeCases(mechanisms, quick);
  // The caller holds each answer to timeout_seconds. A relay gets its answers when the calling thread has answered
  // its batch, taking its turn with every other job's requests: its budget (per request times its n requests, n at
  // least the smallest batch, runGrade's split) covers every request of the grade at the timeout plus 1 s each. It
  // only ends a grade whose caller does not answer at all.
  const size_t total = std::max<size_t>(1, cases.size());
  const size_t batches = std::max<size_t>(1, std::min<size_t>(static_cast<size_t>(run->jobs), total));
  const size_t smallest = std::max<size_t>(1, total / batches);
  settings.relay_timeout_seconds = (timeout_seconds + 1.0) * static_cast<double>(total) / static_cast<double>(smallest);
  run->bridge = std::make_unique<InProcessGrade>(std::move(cases), settings);
  return run;
}

// The next request as (id, scene, phi [rad], case id, family), or None when none came within `wait_seconds` or the
// grade is over (finished). Waits with the GIL released.
py::object nextRequest(GradeRun& run, double wait_seconds) {
  std::optional<InProcessGrade::Request> request;
  {
    py::gil_scoped_release release;
    request = run.bridge->next(std::chrono::milliseconds(static_cast<long long>(wait_seconds * 1000.0)));
  }
  if (!request) return py::none();
  const validation::GradeCase& c = *request->grade_case;
  py::array_t<double> phi(static_cast<py::ssize_t>(c.phi_deg.size()));
  for (size_t i = 0; i < c.phi_deg.size(); ++i) phi.mutable_data()[i] = radiansFromDegrees(c.phi_deg[i]);
  return py::make_tuple(request->id, std::make_shared<Scene>(Scene{c.mechanism, c.id}), phi, c.id, c.family);
}

// The tables as {name: {"columns": [...], "rows": [[...], ...]}}: each cell a float, a str, or None where empty.
py::dict tablesToPython(const validation::TableSet& tables) {
  py::dict d;
  for (const auto& [name, table] : tables) {
    py::list rows;
    for (size_t r = 0; r < table.size(); ++r) {
      py::list row;
      for (size_t c = 0; c < table.columns().size(); ++c) {
        const validation::Cell cell = table.cell(r, c);
        if (const double* x = std::get_if<double>(&cell)) row.append(py::float_(*x));
        else if (const std::string* text = std::get_if<std::string>(&cell)) row.append(py::str(*text));
        else row.append(py::none());
      }
      rows.append(row);
    }
    py::dict t;
    t["columns"] = table.names();
    t["rows"] = rows;
    d[py::str(name)] = t;
  }
  return d;
}

// After finished(): the tables, the exit status and the report (out=).
py::dict gradeResult(GradeRun& run) {
  validation::TableSet tables;
  {
    py::gil_scoped_release release;
    try {
      tables = run.bridge->result();
    } catch (const EnvironmentError& e) {
      // runGrade names the program it started (the relay) and the CLI's flag: say it in this call's words.
      std::string what = e.what();
      auto replace = [&what](const std::string& from, const std::string& to) {
        for (size_t at = what.find(from); at != std::string::npos; at = what.find(from, at + to.size()))
          what.replace(at, from.size(), to);
      };
      replace(run.relay + ": ", "crankcheck.grade: " + run.program_name + ": ");
      replace("--timeout sets the time per request", "timeout= sets the seconds per request");
      throw EnvironmentError(what);
    }
  }
  const std::vector<validation::GradeCase>& cases = run.bridge->cases();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - run.start).count();
  py::dict result;
  result["tables"] = tablesToPython(tables);
  result["exit_status"] = validation::findGradeExitStatus(tables);
  result["cases"] = cases.size();
  result["seconds"] = seconds;
  result["jobs"] = run.jobs;
  if (run.folder) {
    run.info.program = {run.program_name};
    run.info.quick = run.quick;
    run.info.batch = true;
    run.info.jobs = run.jobs;
    run.info.timeout_seconds = run.timeout_seconds;
    run.info.seconds = seconds;
    py::gil_scoped_release release;
    run.folder->createStaging();
    validation::renderGradeReport(tables, cases, run.info, run.folder->getStaging());
    run.folder->install("report");
  }
  result["report"] = run.out_dir ? py::object(py::str(*run.out_dir + "/index.md")) : py::object(py::none());
  return result;
}

// crankcheck.grade_free_run (__init__.py): the runs of `crankcheck grade --free-run` answered by `answer(request line)
// -> response line`, a Python callable that calls the user's function under the per-run timeout; graded by the CLI's
// own code (validation::gradeRunAnswers), so the measures, tolerances, refusals and report are the CLI's.
py::dict gradeFreeRun(const std::vector<py::object>& scenes, const std::string& drive, int revolutions,
                      const std::optional<double>& dt, bool own_step, int dt_sweep,
                      const std::optional<double>& output_interval,
                      const std::vector<std::optional<double>>& tolerances,
                      bool quick, double timeout_seconds, const std::optional<py::object>& out,
                      const py::function& answer, const std::string& program_name, double work_limit) {
  if (scenes.empty()) throw py::value_error("scenes: give at least one scene (a scene with [flywheel] for a free run)");
  if (drive != "free" && drive != "held" && drive != "loaded")
    throw py::value_error("drive: \"free\", \"held\" or \"loaded\", not \"" + drive + "\"");
  if (tolerances.size() != 5) throw std::logic_error("gradeFreeRun: five tolerances");
  for (const std::optional<double>& t : tolerances)
    if (t && (!(*t >= 0.0) || !std::isfinite(*t))) throw py::value_error("tolerances: each a finite number >= 0");
  validation::RunSettings settings;
  settings.drive = drive == "held"     ? validation::RunDrive::kHeld
                   : drive == "loaded" ? validation::RunDrive::kLoaded
                                       : validation::RunDrive::kFree;
  settings.revolutions = revolutions;
  settings.dt = dt;
  settings.own_step = own_step;
  settings.dt_sweep = dt_sweep;
  settings.output_interval = output_interval;
  validation::RunTolerances& t = settings.tolerances;  // a tolerance not given: the CLI's default
  for (auto [given, into] : {std::pair{tolerances[0], &t.energy_trend}, std::pair{tolerances[1], &t.delta},
                             std::pair{tolerances[2], &t.extreme_phase}, std::pair{tolerances[3], &t.phase},
                             std::pair{tolerances[4], &t.values}})
    if (given) *into = *given;
  std::vector<validation::RunCase> cases;
  std::set<std::string> names;
  for (const py::object& item : scenes) {
    const ScenePtr scene = py::isinstance<Scene>(item) ? item.cast<ScenePtr>() : loadScene(item);
    if (!names.insert(scene->m.name).second)
      throw SceneError(scene->source + ": a scene named " + scene->m.name + " is given twice");
    try {
      for (validation::RunCase& c : validation::buildRunCases(scene->m, settings)) cases.push_back(std::move(c));
    } catch (const UsageError& e) {
      throw SceneError(scene->source + ": " + e.what());
    }
  }
  std::unique_ptr<validation::OutputFolder> folder;
  std::optional<std::string> out_dir;
  validation::RunGradeReportInfo info;
  if (out) {
    out_dir = pathArgument(*out);
    if (hasNul(*out_dir)) throw py::value_error("out: " + quotePath(*out_dir) + ": a path with a NUL byte (no folder has that name)");
    folder = std::make_unique<validation::OutputFolder>(*out_dir, "out");
    info.gnuplot_version = validation::checkGnuplot();
  }
  if (!(work_limit >= 1.0) || !std::isfinite(work_limit))
    throw py::value_error("work_limit: seconds, a finite number >= 1");
  try {  // crankcheck's own work over the horizon, estimated before the function is called (as the CLI's --work-limit)
    py::gil_scoped_release release;
    validation::checkRunGradeWork(cases, quick, work_limit);
  } catch (const UsageError& e) {
    std::string message = e.what();
    const std::string flag = validation::kWorkLimitFlag;
    // The CLI's flags as this function's arguments.
    for (size_t at; (at = message.find(flag)) != std::string::npos;) message.replace(at, flag.size(), "work_limit");
    for (size_t at; (at = message.find("--revolutions")) != std::string::npos;) message.replace(at, 13, "revolutions");
    throw py::value_error("crankcheck.grade_free_run: " + message);
  }
  const std::string name = escapeText(program_name);
  const auto start = std::chrono::steady_clock::now();
  validation::TableSet tables = validation::gradeRunAnswers(
      cases, [&](const validation::RunCase& c) { return answer(validation::makeRunRequest(c)).cast<std::string>(); },
      settings.tolerances, "crankcheck.grade_free_run: " + name);
  {
    py::gil_scoped_release release;
    validation::addEngineRuns(tables, cases, quick);  // the engines' own runs beside the function's, as the CLI's
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  py::dict result;
  result["tables"] = tablesToPython(tables);
  result["exit_status"] = validation::findRunGradeExitStatus(tables);
  result["runs"] = cases.size();
  result["seconds"] = seconds;
  if (folder) {
    info.program = {name};
    info.seconds = seconds;
    info.timeout_seconds = timeout_seconds;
    info.tolerances = settings.tolerances;
    folder->createStaging();
    validation::renderRunGradeReport(tables, cases, info, folder->getStaging());
    folder->install("report");
  }
  result["report"] = out_dir ? py::object(py::str(*out_dir + "/index.md")) : py::object(py::none());
  return result;
}

// ---- Plain functions of lambda.
Mechanism unitSliderCrank(double lambda, double r, double omega) {
  if (!(lambda > 0.0 && lambda < 1.0)) throw py::value_error("lam: must be in (0, 1) (lambda = r / l)");
  if (!(r > 0.0) || !std::isfinite(r)) throw py::value_error("r: must be a positive finite length [m]");
  if (!std::isfinite(omega)) throw py::value_error("omega: must be finite [rad/s]");
  Mechanism m;
  m.crank.radius = r;
  m.rod.length = r / lambda;
  m.machine.speed = omega;
  return m;
}

// x_p, v_p, a_p, j_p at each theta, by `f(m, theta)`.
template <class F>
py::dict pistonKinematics(const py::handle& theta_in, const Mechanism& m, F f) {
  const Angles theta = asAngles(theta_in, "theta");
  checkAngles(spanOf(theta), "theta");
  std::vector<py::ssize_t> shape(theta.shape(), theta.shape() + theta.ndim());
  py::array_t<double> x(shape), v(shape), a(shape), j(shape);
  {
    double *px = x.mutable_data(), *pv = v.mutable_data(), *pa = a.mutable_data(), *pj = j.mutable_data();
    const double* t = theta.data();
    const size_t n = static_cast<size_t>(theta.size());
    py::gil_scoped_release release;
    for (size_t i = 0; i < n; ++i) {
      const analytic::PistonKinematics k = f(m, t[i]);
      px[i] = k.x_p;
      pv[i] = k.v_p;
      pa[i] = k.a_p;
      pj[i] = k.j_p;
    }
  }
  py::dict d;
  auto out = [&](py::array_t<double>& arr) -> py::object {
    return arr.ndim() == 0 ? py::object(arr[py::tuple()]) : py::object(arr);
  };
  d["x_p"] = out(x);
  d["v_p"] = out(v);
  d["a_p"] = out(a);
  d["j_p"] = out(j);
  return d;
}

// The largest order the coefficient functions take: their cost grows with the square of the order (0.02 s at 1e4;
// 1e7 would take hours), and no crank ratio below 0.999 has a coefficient above rounding past it.
constexpr int kMaxCoefficientOrder = 10000;

template <class F>
py::array_t<double> coefficients(F f, double lambda, int order) {
  if (order > kMaxCoefficientOrder)
    throw py::value_error("order: at most " + std::to_string(kMaxCoefficientOrder) + " (got " + std::to_string(order) +
                          "): the cost grows with its square");
  try {
    return toArray(f(lambda, order));
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

std::string int128ToString(analytic::Int128 x) {
  // |x| fits: the coefficients are far from the type's limits (calcLambdaSeriesCoefficient throws before overflow).
  const bool negative = x < 0;
  if (negative) x = -x;
  std::string digits;
  do {
    digits.insert(digits.begin(), static_cast<char>('0' + static_cast<int>(x % 10)));
    x /= 10;
  } while (x > 0);
  return negative ? "-" + digits : digits;
}

}  // namespace
}  // namespace crankcheck::python

PYBIND11_MODULE(_crankcheck, mod) {
  using namespace crankcheck;
  using namespace crankcheck::python;
  mod.doc() = "crankcheck's engines over NumPy arrays (the compiled part; import crankcheck).";
  // pybind11 initialises its NumPy API table in a function-local static on first use, importing numpy under the
  // static's guard; first used from two threads at once (crankcheck.grade's answers), the import releasing the GIL
  // lets the second thread take the GIL and wait for the guard: a deadlock. Initialise it here, on the importing thread.
  (void)py::array_t<double>(0);

  // SceneError: a ValueError whose message is the CLI's line without "crankcheck: ". Bad usage is a ValueError, a
  // failed environment (gnuplot missing, a graded function's answer timed out) a RuntimeError.
  py::register_exception<SceneError>(mod, "SceneError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const EnvironmentError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  py::class_<Scene, std::shared_ptr<Scene>>(mod, "Scene", R"doc(
A scene (a mechanism), read from a TOML scene file as `crankcheck eval` reads it. Every value is in SI units and
radians. Immutable; thread-safe (every call builds its own engine model).)doc")
      .def_static(
          "load",
          [](const py::object& path) { return loadScene(path); }, py::arg("path"),
          "Reads and checks a scene file (a str, bytes or os.PathLike path). Raises SceneError with the CLI's message "
          "(file, key, rule); a path with a NUL byte is refused so too (C would read another file's name).")
      .def_static(
          "from_toml",
          [](const std::string& text, const std::string& source) {
            if (hasNul(source)) throw py::value_error("source: " + quoteText(source) + ": a name with a NUL byte");
            return std::make_shared<Scene>(Scene{parseScene(text, source), source});
          },
          py::arg("text"), py::arg("source") = "<string>",
          "Parses scene text; `source` names it in messages (and its stem is the scene's name; a NUL byte is refused). "
          "Raises SceneError.")
      .def_property_readonly("name", [](const Scene& s) { return s.m.name; }, "The scene's name: its file's stem.")
      .def_property_readonly("source", [](const Scene& s) { return s.source; }, "The path or source name messages use.")
      .def_property_readonly("crank_ratio", [](const Scene& s) { return calcCrankRatio(s.m); }, "lambda = r / l.")
      .def_property_readonly("speed_rpm", [](const Scene& s) { return s.m.speed_rpm; }, "The speed as the file gives it [rpm].")
      .def_property_readonly("batch_kernels", [](const Scene& s) { return batchKernelsAccept(s.m); },
                             "Whether evaluate(engine=\"analytic\") runs the SIMD batch kernels for this scene (they cover "
                             "centric cylinders without balance shafts); otherwise it runs the analytic engine's scalar "
                             "closed forms angle by angle, in C++.")
      .def("to_dict", [](const Scene& s) { return toPython(validation::sceneToJson(s.m)); },
           "The parsed scene as `crankcheck eval --format json` prints it under \"scene\" (SI, plus lambda).")
      .def("to_toml", [](const Scene& s) { return formatSceneToml(s.m); },
           "The scene as a scene file that reads back to the same mechanism (formatSceneToml).")
      .def("scales", [](const Scene& s) {
            const validation::Scales sc = validation::calcScales(s.m);
            py::dict d;
            d["energy"] = sc.energy;
            d["absolute_height_energy"] = sc.absolute_height_energy;
            d["position"] = sc.position;
            d["velocity"] = sc.velocity;
            d["acceleration"] = sc.acceleration;
            d["force"] = sc.force;
            d["torque"] = sc.torque;
            d["moment"] = sc.moment;
            d["conditioning"] = sc.conditioning;
            d["velocity_conditioning"] = sc.velocity_conditioning;
            d["acceleration_conditioning"] = sc.acceleration_conditioning;
            d["closure"] = sc.closure;
            return d;
          }, "The physical scales of the scene and the conditioning of comparisons (validation/scales.h), the gate's.")
      .def("evaluate", &evaluate, py::arg("phi"), py::arg("engine") = validation::getClosedFormEngine().name, py::arg("quantities") = py::none(),
           py::kw_only(), py::arg("out") = py::none(),
           R"doc(
Every quantity of `crankcheck eval` at the crank angles `phi` [rad] (a NumPy array of any shape, or a float; any
finite angle: beyond 4 pi in magnitude it is reduced to rounding first, see docs/safety.md "Angles of any size") by
`engine` (any name of crankcheck.engines()). Returns a dict of NumPy arrays named as eval's JSON: U, Q, U_star, Q_star
(None without a flywheel or at rest), drive_torque with phi's shape; bearing_force, shaking_force (..., 2);
shaking_moment (..., 3), X and Y NaN without axial positions (eval: null); per cylinder x_p, v_p, a_p, wall_force,
gas_force (only with [gas]), rod_angle, rod_omega, rod_alpha (..., k) and crank_pin_force, wrist_pin_force (..., k, 2).
`quantities`: compute only these names. `out`: a dict an earlier call returned (the same scene, phi's shape and
quantities): its arrays are written again and it is returned (no new memory). The analytic engine runs the SIMD batch kernels on phi's own buffer (a
C-contiguous float64 array is not copied); other engines run angle by angle in C++. The GIL is released.)doc")
      .def("balance", &balance, py::arg("order") = 8,
           "Harmonics 1..order of the shaking force and moment: `crankcheck balance SCENE --order N --format json` as a dict "
           "(without its words, \"reason\": \"vanishes_by_symmetry\" says what vanishes exactly).")
      .def("motion", &motion, py::kw_only(), py::arg("integrator") = "RungeKuttaMerson", py::arg("accuracy") = 1e-10,
           py::arg("mujoco_integrator") = "RK4", py::arg("mujoco_step") = 1e-3,
           py::arg("stepped_step") = validation::kDefaultSteppedMotionStep, py::arg("stepped_settings") = "defaults",
           py::arg("series") = false,
           "The free run: `crankcheck motion SCENE --format json` as a dict (series=True adds each integrating engine's "
           "run with gravity: time [s], phi [rad], phi_dot [rad/s], energy [J]).")
      .def("__repr__", [](const Scene& s) {
        return "<crankcheck.Scene " + s.m.name + " (" + s.source + "): k = " + std::to_string(s.m.machine.cylinders) +
               ", lambda = " + validation::formatNumber(calcCrankRatio(s.m)) + ", " + validation::formatNumber(s.m.speed_rpm) + " rpm>";
      });

  mod.def("engines", [](const std::string& route) {
        // The registry's routes by the names Python passes (crankcheck::Route).
        const std::vector<std::pair<std::string, Route>> routes = {
            {"evaluate", Route::kEvaluate}, {"simulate", Route::kSimulate}, {"step_at_speed", Route::kStepAtSpeed},
            {"step_free", Route::kStepFree}, {"crank_train", Route::kCrankTrain}};
        std::vector<const Engine*> chosen;
        auto add = [&](Route r) {
          for (const Engine& e : validation::listEngines(r))
            if (std::find(chosen.begin(), chosen.end(), &e) == chosen.end()) chosen.push_back(&e);
        };
        std::string names;
        for (const auto& [name, r] : routes) {
          names += (names.empty() ? "" : ", ") + name;
          if (route == name || route == "all") add(r);
        }
        if (chosen.empty() && route != "all")
          throw py::value_error("route: " + escapeText(route) + " not in {" + names + ", all}");
        py::list list;
        for (const Engine* e : chosen) {
          py::dict d;
          d["name"] = e->name;
          d["library"] = e->library;
          d["method"] = e->method;
          d["gated"] = e->gated;
          d["integrators"] = e->integrators;
          d["settings"] = e->settings;
          std::vector<std::string> offered;
          for (const auto& [name, r] : routes)
            if (offersRoute(*e, r)) offered.push_back(name);
          d["routes"] = offered;
          list.append(d);
        }
        return list;
      }, py::arg("route") = "evaluate",
      "The engines of the registry (validation::listEngines(route)) offering `route`, in its order: \"evaluate\" (the "
      "default: every engine eval and Scene.evaluate take), \"simulate\", \"step_at_speed\", \"step_free\", "
      "\"crank_train\", or \"all\". Each: name, library, method, gated, integrators (Scene.motion's), settings (the "
      "stepped routes'), routes (what it offers).");
  mod.def("quantities", [] {
        py::list list;
        for (const QuantityInfo& q : listQuantities()) list.append(q.name);
        return list;
      }, "The names Scene.evaluate returns, in eval's order.");
  mod.def("free_run_tolerances", [] {
        const validation::RunTolerances t;  // free_run_grade.h: the defaults of grade --free-run and grade_free_run
        py::dict d;
        d["energy_tolerance"] = t.energy_trend;
        d["delta_tolerance"] = t.delta;
        d["extreme_phase_tolerance"] = t.extreme_phase;
        d["phase_tolerance"] = t.phase;
        d["values_tolerance"] = t.values;
        return d;
      }, "The default tolerances of crankcheck.grade_free_run (and grade --free-run), by keyword.");
  mod.def("_per_cylinder_quantities", [] {
        py::list list;  // the catalogue's per-cylinder quantities (scene/quantities.h): grade_free_run's columns (n, k)
        for (const Quantity& q : getQuantityCatalogue())
          if (q.per_cylinder) list.append(q.name);
        return list;
      });
  mod.def("batch_target", [] { return std::string(analytic::getBatchTargetName()); },
          "The instruction set the analytic batch kernels run on here (AVX3, AVX2, SSE4, SSSE3 or SCALAR).");
  mod.attr("__version__") = validation::getCrankcheckVersion();

  mod.def("radians_from_degrees", [](const py::handle& degrees_in) {
        const Angles degrees = asAngles(degrees_in, "degrees", "deg");
        for (py::ssize_t i = 0; i < degrees.size(); ++i)
          if (!std::isfinite(degrees.data()[i]))
            throw py::value_error("degrees[" + std::to_string(i) + "] = " + validation::formatNumber(degrees.data()[i]) +
                                  ": must be a finite number of degrees (as --phi-deg)");
        py::array_t<double> radians(std::vector<py::ssize_t>(degrees.shape(), degrees.shape() + degrees.ndim()));
        for (py::ssize_t i = 0; i < degrees.size(); ++i) radians.mutable_data()[i] = crankAngleFromDegrees(degrees.data()[i]);
        return radians.ndim() == 0 ? py::object(radians[py::tuple()]) : py::object(radians);
      }, py::arg("degrees"),
      "Degrees to radians as the CLI converts --phi-deg (beyond 720 degrees reduced exactly modulo 720 first; exact "
      "multiples of 90 degrees become n x (pi/2) exactly, so that sin and cos are exact at quarter turns): the same "
      "angles as `crankcheck eval --phi-deg`.");
  py::class_<GradeRun>(mod, "_GradeRun")
      .def("next", &nextRequest, py::arg("wait_seconds"))
      .def("answer", [](GradeRun& run, size_t id, const py::handle& answer) {
            // The function's answer checked and written as protocol 1's line for its request's case.
            if (const validation::GradeCase* c = run.bridge->caseOf(id)) run.bridge->answer(id, toResponse(*c, answer));
          }, py::arg("id"), py::arg("answer"))
      .def("finished", [](GradeRun& run) { return run.bridge->finished(); })
      .def("stop", [](GradeRun& run) { run.bridge->stop(); }, py::call_guard<py::gil_scoped_release>())
      .def("result", &gradeResult)
      .def("timeout_message", [](const GradeRun& run, const std::string& case_id) {
            // runGrade's words for a program that did not answer a request in time (grade.cc: runOnce), for a call.
            return "crankcheck.grade: " + run.program_name + ": case " + case_id + ": no complete answer within " +
                   validation::formatNumber(run.timeout_seconds) + " s (interrupted; timeout= sets the seconds per request)";
          }, py::arg("case_id"));
  mod.def("_grade_start", &startGrade, py::arg("scenes"), py::arg("quick"), py::arg("jobs"), py::arg("timeout"),
          py::arg("out"), py::arg("relay"), py::arg("program_name"));
  mod.def("_grade_free_run", &gradeFreeRun, py::arg("scenes"), py::arg("drive"), py::arg("revolutions"), py::arg("dt"),
          py::arg("own_step"), py::arg("dt_sweep"), py::arg("output_interval"), py::arg("tolerances"), py::arg("quick"),
          py::arg("timeout"), py::arg("out"), py::arg("answer"), py::arg("program_name"), py::arg("work_limit"));
  mod.def("_raise_in_thread", [](unsigned long thread_id, const py::object& exception) {
        // PyThreadState_SetAsyncExc: `exception` (a class) raised in that thread at its next Python bytecode; None
        // clears one not yet raised. The number of threads changed.
        return PyThreadState_SetAsyncExc(thread_id, exception.is_none() ? nullptr : exception.ptr());
      }, py::arg("thread_id"), py::arg("exception"));
  mod.def("_grade_regimes", [] {
        py::dict regimes;  // the summary's regime ids and their words (grade.h: getGradeRegimes)
        for (const validation::GradeRegime& r : validation::getGradeRegimes()) regimes[py::str(r.id)] = r.words;
        return regimes;
      });
  mod.def("_input_buffer_address", [](const py::handle& phi) {
        return reinterpret_cast<std::uintptr_t>(asAngles(phi).data());
      }, "The address of the angles' buffer as evaluate() uses it (a test that a float64 C-contiguous array is not copied).");

  // Closed forms (fourier_series.h, kinematics.h) as plain functions of lambda.
  mod.def("radical_fourier_coefficients", [](double lam, int order) {
        return coefficients(analytic::calcRadicalFourierCoefficients, lam, order);
      }, py::arg("lam"), py::arg("order"),
      "A_0 .. A_order of sqrt(1 - lam^2 sin^2 theta) = A_0 + sum A_2m cos(2 m theta), exact to double precision.");
  mod.def("inverse_radical_fourier_coefficients", [](double lam, int order) {
        return coefficients(analytic::calcInverseRadicalFourierCoefficients, lam, order);
      }, py::arg("lam"), py::arg("order"), "B_0 .. B_order of 1 / sqrt(1 - lam^2 sin^2 theta).");
  mod.def("lambda_coefficients", [](double lam, int order) {
        return coefficients(analytic::calcLambdaCoefficients, lam, order);
      }, py::arg("lam"), py::arg("order"),
      "Lambda_0 .. Lambda_order of Stanczak eq (14): lam sin cos / sqrt(1 - lam^2 sin^2) = sum Lambda_n sin(n theta).");
  mod.def("lambda_coefficients_as_printed", [](double lam, int order) {
        return coefficients(analytic::calcLambdaCoefficientsAsPrinted, lam, order);
      }, py::arg("lam"), py::arg("order"), "The paper's eq (15) table as printed (truncated at lam^11; see docs/ERRATA.md).");
  mod.def("lambda_series_coefficient", [](int n, int power) {
        analytic::Rational r;
        try {
          r = analytic::calcLambdaSeriesCoefficient(n, power);
        } catch (const std::invalid_argument& e) {
          throw py::value_error(e.what());
        } catch (const std::overflow_error& e) {
          throw py::value_error(e.what());
        }
        py::object integer = py::module_::import("builtins").attr("int");
        return py::module_::import("fractions").attr("Fraction")(integer(int128ToString(r.numerator)),
                                                               integer(int128ToString(r.denominator)));
      }, py::arg("n"), py::arg("power"), "The exact coefficient of lam^power in Lambda_n, a fractions.Fraction.");
  mod.def("piston_kinematics", [](const py::handle& theta, double lam, double r, double omega) {
        return pistonKinematics(theta, unitSliderCrank(lam, r, omega),
                                [](const Mechanism& m, double t) { return analytic::calcPistonKinematics(m, t); });
      }, py::arg("theta"), py::arg("lam"), py::kw_only(), py::arg("r") = 1.0, py::arg("omega") = 1.0,
      "Exact x_p [m], v_p, a_p, j_p of a centric slider-crank (Norton 13.1d and its derivatives) at crank angles theta "
      "[rad], crank r [m], l = r / lam, constant speed omega [rad/s].");
  mod.def("norton_two_term", [](const py::handle& theta, double lam, double r, double omega) {
        return pistonKinematics(theta, unitSliderCrank(lam, r, omega), analytic::calcPistonKinematicsNorton);
      }, py::arg("theta"), py::arg("lam"), py::kw_only(), py::arg("r") = 1.0, py::arg("omega") = 1.0,
      "Norton's two-term forms (13.3c-e) and the derivative of 13.3e: x = l - r^2/(4l) + r (cos + (r/4l) cos 2theta), "
      "v = -r omega (sin + (r/2l) sin 2theta), a = -r omega^2 (cos + (r/l) cos 2theta).");
  mod.def("fourier_piston_kinematics", [](const py::handle& theta, double lam, int order, double r, double omega) {
        if (order < 1) throw py::value_error("order: must be >= 1");
        if (order > kMaxCoefficientOrder)  // the coefficients' cost, per angle (order 1e6 took 144 s for one angle)
          throw py::value_error("order: at most " + std::to_string(kMaxCoefficientOrder) + " (got " +
                                std::to_string(order) + "): the cost grows with its square");
        return pistonKinematics(theta, unitSliderCrank(lam, r, omega), [order](const Mechanism& m, double t) {
          return analytic::calcPistonKinematicsFourier(m, t, order);
        });
      }, py::arg("theta"), py::arg("lam"), py::arg("order"), py::kw_only(), py::arg("r") = 1.0, py::arg("omega") = 1.0,
      "x_p's Fourier series with exact coefficients truncated after harmonic `order`, and its time derivatives.");
}
