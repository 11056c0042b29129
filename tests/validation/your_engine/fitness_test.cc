// Scene topic `fitness` (validation/src/your_engine/fitness.cc): each formula's largest error on a scene as given,
// held against computations written here from first principles in 50-digit arithmetic (boost cpp_bin_float_50): the
// exact slider crank x_p = r cos + sqrt(l^2 - (r sin - delta)^2) and its derivatives, Norton's series, Q = dV/dphi from
// the heights of the moving masses, its harmonics by a numerical Fourier analysis, the two-mass rod's missing inertia
// torque Delta_I omega^2 beta' beta'' (the kinetic energy 1/2 Delta_I beta_dot^2 it leaves out), each maximised over a
// fine grid and refined by golden sections. The issue's acceptance: within 1e-6 relative.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <boost/multiprecision/cpp_bin_float.hpp>

#include "crankcheck/scene/quantities.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/scales.h"
#include "../../../validation/src/your_engine/topic.h"

namespace crankcheck::validation::your_engine {
namespace topics {
const SceneTopic& fitness();
}  // namespace topics
namespace {

using Real = boost::multiprecision::cpp_bin_float_50;

// The issue's acceptance for a formula's error against an independent high-precision model.
constexpr double kAcceptance = 1e-6;

const Real kPi = boost::math::constants::pi<Real>();

// max over phi in [0, 2 pi) of |f|: a grid of `samples`, the 4 best local maxima refined by golden sections to 1e-30 of
// a cell (a smooth maximum's value then exact far beyond double).
Real maxAbsOverTurn(const std::function<Real(const Real&)>& f, int samples) {
  std::vector<Real> v(samples);
  for (int i = 0; i < samples; ++i) v[i] = abs(f(2 * kPi * i / samples));
  std::vector<int> peaks;
  for (int i = 0; i < samples; ++i)
    if (v[i] >= v[(i + samples - 1) % samples] && v[i] >= v[(i + 1) % samples]) peaks.push_back(i);
  std::sort(peaks.begin(), peaks.end(), [&](int a, int b) { return v[a] > v[b]; });
  Real best = 0;
  for (int i : peaks) best = std::max(best, v[i]);
  if (peaks.size() > 4) peaks.resize(4);
  const Real g = (sqrt(Real(5)) - 1) / 2;
  for (int i : peaks) {
    Real a = 2 * kPi * (i - 1) / samples, b = 2 * kPi * (i + 1) / samples;
    Real c = b - g * (b - a), d = a + g * (b - a);
    Real fc = abs(f(c)), fd = abs(f(d));
    for (int it = 0; it < 110; ++it) {  // 0.618^110 ~ 1e-23 of two cells
      if (fc > fd) {
        b = d, d = c, fd = fc, c = b - g * (b - a), fc = abs(f(c));
      } else {
        a = c, c = d, fc = fd, d = a + g * (b - a), fd = abs(f(d));
      }
    }
    best = std::max({best, fc, fd});
  }
  return best;
}

// One cylinder's slider crank in 50 digits: x(theta) and its first two derivatives per radian.
struct Slider {
  Real r, l, delta;
  // u = r sin - delta (the pin's height over the axis), S = sqrt(l^2 - u^2) = l cos(beta).
  Real x(const Real& t) const { return r * cos(t) + sqrt(l * l - sq(r * sin(t) - delta)); }
  Real dx(const Real& t) const {
    const Real u = r * sin(t) - delta, du = r * cos(t);
    return -r * sin(t) - u * du / sqrt(l * l - u * u);
  }
  Real ddx(const Real& t) const {
    const Real u = r * sin(t) - delta, du = r * cos(t), ddu = -r * sin(t), S = sqrt(l * l - u * u);
    return -r * cos(t) - (du * du + u * ddu) / S - u * u * du * du / (S * S * S);
  }
  // beta = asin(u / l): beta' = u' / S, beta'' = u'' / S + u'^2 u / S^3.
  Real dbeta(const Real& t) const { return r * cos(t) / sqrt(l * l - sq(r * sin(t) - delta)); }
  Real ddbeta(const Real& t) const {
    const Real u = r * sin(t) - delta, du = r * cos(t), ddu = -r * sin(t), S = sqrt(l * l - u * u);
    return ddu / S + du * du * u / (S * S * S);
  }
  static Real sq(const Real& a) { return a * a; }
};

Slider sliderOf(const Mechanism& m, int j) { return {m.crank.radius, m.rod.length, getPinOffset(m, j)}; }

// Q = dV/dphi from the heights (gravity along -Y) of the piston and wrist pin (x_p sin gamma), the rod's centre of
// mass (z_k / l of the way from the wrist pin to the crank pin), the crank's centre of mass and counterweight (on the
// crank line at theta + gamma from +X): the rod's share at each pin per `wrist_share` (eq 2: (l - z_k) / l; the
// paper's eq (5) as printed swaps it: z_k / l).
Real gravityTorque(const Mechanism& m, const Real& phi, bool as_printed = false) {
  const Real z = m.rod.com_from_wrist_pin, l = m.rod.length;
  const Real wrist_share = as_printed ? z / l : (l - z) / l, crank_share = 1 - wrist_share;
  Real Q = 0;
  for (int j = 0; j < m.machine.cylinders; ++j) {
    const Real gamma = getBankAngle(m, j), theta = phi + Real(m.machine.crank_angles[j]);
    const Slider s = sliderOf(m, j);
    Q += (m.piston.mass + m.rod.mass * wrist_share) * s.dx(theta) * sin(gamma) +
         (m.rod.mass * crank_share * m.crank.radius + m.crank.mass * m.crank.com_radius -
          m.crank.counterweight_mass * m.crank.counterweight_radius) *
             cos(theta + gamma);
  }
  return Real(m.machine.gravity) * Q;
}

// The harmonics of Q by a numerical Fourier analysis of 64 samples: aliasing brings in harmonic 64 - n, below
// q^30 ~ 1e-40 of Q for lambda <= 0.4 (q = (lambda / (1 + sqrt(1 - lambda^2)))^2).
struct Harmonics {
  std::vector<Real> a, b;  // Q ~ a_0 + sum a_n cos n phi + b_n sin n phi
};
Harmonics analyseQ(const Mechanism& m) {
  const int N = 64;
  std::vector<Real> q(N), c(N), s(N);
  for (int i = 0; i < N; ++i) {
    q[i] = gravityTorque(m, 2 * kPi * i / N);
    c[i] = cos(2 * kPi * i / N);
    s[i] = sin(2 * kPi * i / N);
  }
  Harmonics h{std::vector<Real>(N / 2, 0), std::vector<Real>(N / 2, 0)};
  for (int n = 1; n < N / 2; ++n) {
    for (int i = 0; i < N; ++i) {
      h.a[n] += q[i] * c[(n * i) % N];
      h.b[n] += q[i] * s[(n * i) % N];
    }
    h.a[n] *= Real(2) / N;
    h.b[n] *= Real(2) / N;
  }
  return h;
}

// The topic's rows of `m` (the full campaign's task), computed once per scene.
const TableSet& runTopic(const Mechanism& m, bool quick = false) {
  static std::map<std::string, TableSet> done;
  const std::string key = m.name + (quick ? " quick" : "");
  if (!done.count(key)) {
    TableSet all;
    for (const Task& task : topics::fitness().tasks(m, quick)) appendTables(all, task.run());
    done[key] = std::move(all);
  }
  return done.at(key);
}

// The row of `m` for `order` and `reference` ("analytic" by default), or none.
const FitnessRow* findRow(const TableSet& tables, int order, const std::string& reference = "analytic") {
  for (const FitnessRow& row : getRows(tables, kFitnessTable))
    if (row.order == order && row.reference == reference) return &row;
  return nullptr;
}

// The relative difference of a row's largest error from an independent one [SI].
void expectMatches(const FitnessRow* row, const Real& independent_abs) {
  ASSERT_NE(row, nullptr);
  SCOPED_TRACE(row->formula + " " + row->quantity);
  const double independent = static_cast<double>(independent_abs);
  EXPECT_EQ(row->resolved, 1);
  EXPECT_NEAR(row->max_error_rel * row->scale_value, independent, kAcceptance * independent);
}

// The scenes built here: a V-twin with gas, an offset single with gas, a bare inline three.
const char* const kVTwin = R"(format_version = 1
name = "V-twin"
[engine]
cycle = "four-stroke"
speed_rpm = 5500
[[cylinder]]
bank_angle_deg = 45.0
throw_angle_deg = 0.0
firing_angle_deg = 45.0
[[cylinder]]
bank_angle_deg = 135.0
throw_angle_deg = 0.0
firing_angle_deg = 495.0
[crank]
radius = 0.04
mass = 1.0
com_radius = 0.02
counterweight_mass = 0.9
counterweight_radius = 0.03
[rod]
length = 0.13
mass = 0.45
com_from_wrist_pin = 0.09
inertia_about_wrist_pin = 0.0045
[piston]
mass = 0.4
[gas]
bore = 0.09
cycle_angle_deg = [0, 30, 90, 180, 360, 540, 690]
pressure_pa = [4.0e6, 3.0e6, 1.0e6, 0.3e6, 0.0, 0.05e6, 1.5e6]
)";
const char* const kOffsetSingle = R"(format_version = 1
name = "Offset single"
[engine]
cylinders = 1
cycle = "four-stroke"
cylinder_angle_deg = 90
speed_rpm = 4000
pin_offset = 0.012
[crank]
radius = 0.05
mass = 1.2
com_radius = 0.02
counterweight_mass = 0.8
counterweight_radius = 0.035
[rod]
length = 0.15
mass = 0.55
com_from_wrist_pin = 0.105
inertia_about_wrist_pin = 0.0075
[piston]
mass = 0.35
[gas]
bore = 0.1
cycle_angle_deg = [0, 30, 90, 180, 360, 540, 690]
pressure_pa = [4.0e6, 3.0e6, 1.0e6, 0.3e6, 0.0, 0.05e6, 1.5e6]
firing_order = [0]
)";
const char* const kBareInline3 = R"(format_version = 1
name = "Bare inline three"
[engine]
cylinders = 3
cycle = "two-stroke"
cylinder_angle_deg = 70
speed_rpm = 3000
[crank]
radius = 0.045
mass = 1.0
com_radius = 0.02
counterweight_mass = 0.5
counterweight_radius = 0.03
[rod]
length = 0.12
mass = 0.4
com_from_wrist_pin = 0.08
inertia_about_wrist_pin = 0.004
[piston]
mass = 0.3
)";

Mechanism sceneFromText(const char* text, const std::string& stem) {
  Mechanism m = parseScene(text, stem + ".toml");
  m.name = stem;
  return m;
}

std::vector<Mechanism> listTestScenes() {
  std::vector<Mechanism> out = loadExampleScenes();
  out.push_back(sceneFromText(kVTwin, "v_twin_gas"));
  out.push_back(sceneFromText(kOffsetSingle, "offset_single_gas"));
  out.push_back(sceneFromText(kBareInline3, "bare_inline3"));
  return out;
}

class FitnessSceneTest : public ::testing::TestWithParam<Mechanism> {};

// Norton's two-term x_p, v_p, a_p against the exact slider crank: every cylinder's error is one function of its own
// angle theta (the cylinders differ by their pin offsets alone), so the largest over the cycle is that over theta.
TEST_P(FitnessSceneTest, NortonAgainstTheExactSliderCrank) {
  const Mechanism& m = GetParam();
  const TableSet& tables = runTopic(m);
  const Real r = m.crank.radius, l = m.rod.length, w = m.machine.speed;
  Real x = 0, v = 0, a = 0;
  for (int j = 0; j < m.machine.cylinders; ++j) {
    const Slider s = sliderOf(m, j);
    x = std::max(x, maxAbsOverTurn([&](const Real& t) {
      return l - r * r / (4 * l) + r * (cos(t) + r / (4 * l) * cos(2 * t)) - s.x(t); }, 720));
    v = std::max(v, maxAbsOverTurn([&](const Real& t) { return -r * (sin(t) + r / (2 * l) * sin(2 * t)) - s.dx(t); }, 720));
    a = std::max(a, maxAbsOverTurn([&](const Real& t) { return -r * (cos(t) + r / l * cos(2 * t)) - s.ddx(t); }, 720));
  }
  expectMatches(findRow(tables, 0), x);
  expectMatches(findRow(tables, 1), w * v);
  expectMatches(findRow(tables, 2), w * w * a);
  EXPECT_DOUBLE_EQ(findRow(tables, 2)->scale_value, m.crank.radius * m.machine.speed * m.machine.speed);
}

// Q's series truncated at orders 2..12 against a numerical Fourier analysis of Q (from the masses' heights), where the
// paper's series apply (one bank, centric, no balance shafts) and Q does not vanish; eq (5) as printed everywhere.
TEST_P(FitnessSceneTest, GravityFormulasAgainstAFourierAnalysisOfQ) {
  const Mechanism& m = GetParam();
  const TableSet& tables = runTopic(m);
  const Real max_Q = maxAbsOverTurn([&](const Real& phi) { return gravityTorque(m, phi); }, 720);
  const bool series = isSingleBank(m) && !hasPinOffsets(m) && m.balance_shafts.empty();
  if (max_Q < 1e-9 * calcEnergyScale(m)) {  // Q vanishes by symmetry: every row a bound against the energy scale
    for (const FitnessRow& row : getRows(tables, kFitnessTable))
      if (row.quantity == "Q") {
        EXPECT_EQ(row.resolved, 0) << row.formula;
        EXPECT_EQ(row.scale, "energy scale E");
      }
    return;
  }
  if (series) {
    const Harmonics h = analyseQ(m);
    for (int order : {2, 4, 6, 8, 10, 12}) {
      const Real rest = maxAbsOverTurn([&](const Real& phi) {
        // cos n phi, sin n phi by angle addition from n = 1 (two sines per angle rather than 60)
        const Real c1 = cos(phi), s1 = sin(phi);
        Real c = c1, s = s1, sum = 0;
        for (size_t n = 1; n < h.a.size(); ++n) {
          if (static_cast<int>(n) > order) sum += h.a[n] * c + h.b[n] * s;
          const Real next = c * c1 - s * s1;
          s = s * c1 + c * s1;
          c = next;
        }
        return sum;
      }, 360);
      const FitnessRow* row = findRow(tables, 10 + order / 2 - 1);
      ASSERT_NE(row, nullptr) << order;
      EXPECT_NEAR(row->scale_value, static_cast<double>(max_Q), kAcceptance * static_cast<double>(max_Q));
      if (rest > 1e-12 * max_Q) expectMatches(row, rest);  // else the remainder is below double's reach of Q
    }
  } else {
    EXPECT_EQ(findRow(tables, 10), nullptr) << "the series do not apply to this scene";
    EXPECT_EQ(findRow(tables, 16), nullptr);
  }
  const Real printed = maxAbsOverTurn([&](const Real& phi) { return gravityTorque(m, phi, true) - gravityTorque(m, phi); }, 720);
  if (printed > 1e-9 * max_Q) expectMatches(findRow(tables, 17), printed);
}

// The two-mass rod without Delta_I leaves out the kinetic energy 1/2 Delta_I beta_dot^2: at constant omega its drive
// torque is short by d/dt(1/2 Delta_I beta_dot^2) / omega = Delta_I omega^2 beta' beta'' per cylinder (the gas, the
// gravity and the other inertia are the same in both); with Delta_I it is exact (a bound at rounding).
TEST_P(FitnessSceneTest, TwoMassRodAgainstTheMissingInertiaTorque) {
  const Mechanism& m = GetParam();
  const TableSet& tables = runTopic(m);
  const Real delta_I = Real(m.rod.inertia_about_wrist_pin) - Real(m.rod.mass) * m.rod.com_from_wrist_pin * m.rod.length;
  const Real w = m.machine.speed;
  const Real missing = maxAbsOverTurn([&](const Real& phi) {
    Real sum = 0;
    for (int j = 0; j < m.machine.cylinders; ++j) {
      const Slider s = sliderOf(m, j);
      const Real theta = phi + Real(m.machine.crank_angles[j]);
      sum += delta_I * w * w * s.dbeta(theta) * s.ddbeta(theta);
    }
    return sum;
  }, 720);
  expectMatches(findRow(tables, 20), missing);
  EXPECT_EQ(findRow(tables, 21)->resolved, 0) << "the paper's two-mass rod with Delta_I is exact";
}

// On a scene with pin offsets: the centric x_p and a_p against the offset slider crank, relative to the stroke and
// r omega^2.
TEST_P(FitnessSceneTest, CentricFormsAgainstTheOffsetSliderCrank) {
  const Mechanism& m = GetParam();
  const TableSet& tables = runTopic(m);
  if (!hasPinOffsets(m)) {
    EXPECT_EQ(findRow(tables, 30), nullptr);
    return;
  }
  const Real w = m.machine.speed;
  Real x = 0, a = 0, stroke = 0;
  for (int j = 0; j < m.machine.cylinders; ++j) {
    const Slider s = sliderOf(m, j), centric{s.r, s.l, 0};
    x = std::max(x, maxAbsOverTurn([&](const Real& t) { return centric.x(t) - s.x(t); }, 720));
    a = std::max(a, maxAbsOverTurn([&](const Real& t) { return centric.ddx(t) - s.ddx(t); }, 720));
    stroke = std::max(stroke, sqrt(Slider::sq(s.l + s.r) - s.delta * s.delta) - sqrt(Slider::sq(s.l - s.r) - s.delta * s.delta));
  }
  expectMatches(findRow(tables, 30), x);
  EXPECT_NEAR(findRow(tables, 30)->scale_value, static_cast<double>(stroke), 1e-15 * static_cast<double>(stroke));
  expectMatches(findRow(tables, 31), w * w * a);
}

// Each reference engine's error of a formula is the analytic one's: the engines agree to 64 eps of the gate's scales
// times their conditioning (about 1e-13 of each scale here), which is up to 100 times more of a row's own scale (max
// |Q| against the energy scale); 1e-9 keeps a margin. Every formula has a row per reference engine.
TEST_P(FitnessSceneTest, ReferenceEnginesAgreeWithTheClosedForms) {
  const Mechanism& m = GetParam();
  const TableSet& tables = runTopic(m);
  int compared = 0;
  for (const FitnessRow& row : getRows(tables, kFitnessTable)) {
    EXPECT_EQ(row.scene, m.name);
    EXPECT_GT(row.scale_value, 0.0);
    if (row.reference != "analytic") continue;
    for (const Engine* engine : listReferenceEngines()) {
      const FitnessRow* other = findRow(tables, row.order, engine->name);
      ASSERT_NE(other, nullptr) << row.formula << " " << engine->name;
      if (row.resolved) {
        EXPECT_NEAR(other->max_error_rel, row.max_error_rel, 1e-9) << row.formula << " " << engine->name;
      } else {
        EXPECT_LT(other->max_error_rel, 1e-9) << row.formula << " " << engine->name;
      }
      ++compared;
    }
  }
  EXPECT_GT(compared, 0);
}

// The rows read back through their schema (the report is rendered again from CSV).
TEST_P(FitnessSceneTest, RowsReadBackThroughTheSchema) {
  const TableSet& tables = runTopic(GetParam());
  for (const TableSchema* schema : topics::fitness().schemas()) {
    const Table& table = tables.at(schema->name());
    const std::string csv = formatCsv(table);
    const Table back = parseTable(schema->name(), parseCsv(csv, schema->name()), schema->name(), findTableSchema(schema->name()));
    EXPECT_EQ(formatCsv(back), csv) << schema->name();
  }
  EXPECT_EQ(getRows(tables, kFitnessTable).size() % (1 + listReferenceEngines().size()), 0u);
}

INSTANTIATE_TEST_SUITE_P(Scenes, FitnessSceneTest, ::testing::ValuesIn(listTestScenes()),
                         [](const ::testing::TestParamInfo<Mechanism>& info) { return info.param.name; });

// The paragraph of what is not judged, from the tables alone: the V-twin's several banks, the inline three's lack of
// pin offsets; an offset scene's series left out for its offsets.
TEST(FitnessDescribeTest, SaysWhatIsNotJudgedAndWhy) {
  auto text = [](const Mechanism& m) {
    std::string all;
    for (const ReportBlock& b : topics::fitness().describe(runTopic(m), m.name)) {
      all += b.text + "\n";
      for (const auto& row : b.rows)
        for (const std::string& cell : row) all += cell + "|";
    }
    return all;
  };
  const std::string v_twin = text(sceneFromText(kVTwin, "v_twin_gas"));
  EXPECT_NE(v_twin.find("Not judged on this scene: Q's Fourier series (orders 2-12) and eq (15): the paper's series are for "
                        "one bank of centric cylinders without balance shafts; this scene has several banks"),
            std::string::npos) << v_twin;
  // Eq (5) is judged beyond the series' domain, and the paragraph says why (issue 59).
  EXPECT_NE(v_twin.find("(eq (5) is judged all the same: its U1 and U2 are one cylinder's masses split between its pins"),
            std::string::npos) << v_twin;
  EXPECT_NE(v_twin.find("Norton's two-term series (eq 13.3)|a_p|"), std::string::npos) << v_twin;
  const std::string bare = text(sceneFromText(kBareInline3, "bare_inline3"));
  EXPECT_NE(bare.find("centric forms (delta = 0): no pin offsets"), std::string::npos) << bare;
  EXPECT_NE(bare.find("docs/SCENE-FORMAT.md"), std::string::npos);
  EXPECT_NE(bare.find("Fourier series of Q to order 12 (exact Lambda_n)|Q|"), std::string::npos) << bare;
  const std::string offset = text(sceneFromText(kOffsetSingle, "offset_single_gas"));
  EXPECT_NE(offset.find("this scene has pin offsets"), std::string::npos) << offset;
  EXPECT_NE(offset.find("centric forms (delta = 0)|x_p|"), std::string::npos) << offset;
  // Another scene's name: nothing of it.
  EXPECT_EQ(topics::fitness().describe(runTopic(sceneFromText(kVTwin, "v_twin_gas")), "bare_inline3").size(), 0u);
}

// The quick campaign's coarser grids give the same maxima (refined): well within the 1 % the quick report test asks.
TEST(FitnessQuickTest, QuickMaximaAreTheFullOnes) {
  const Mechanism m = sceneFromText(kVTwin, "v_twin_gas");
  const std::vector<FitnessRow> quick = getRows(runTopic(m, true), kFitnessTable), full = getRows(runTopic(m), kFitnessTable);
  ASSERT_EQ(quick.size(), full.size());
  for (size_t i = 0; i < quick.size(); ++i) {
    EXPECT_EQ(quick[i].resolved, full[i].resolved) << full[i].formula;
    if (full[i].resolved) {
      EXPECT_NEAR(quick[i].max_error_rel, full[i].max_error_rel, 1e-9 * full[i].max_error_rel) << full[i].formula;
    }
  }
}

}  // namespace
}  // namespace crankcheck::validation::your_engine
