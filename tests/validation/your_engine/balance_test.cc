// The scene sections' topic "Balance" (validation/src/your_engine/balance.cc) against an independent model of each
// scene written here: the positions of every moving mass (pistons on their exact slider-crank loop, rod centres,
// throw masses, balance shaft masses) and every rod's angle in 50-digit arithmetic (cpp_bin_float_50), their
// accelerations at constant speed by central second differences of those positions, the shaking force -sum m a and
// moment -sum p x m a - I_G psi_ddot Z summed here, and their harmonics by a DFT written here. No closed form of the
// library enters it (no Fourier series, no shaking.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include "../../../validation/src/your_engine/topic.h"
#include "scene_section_fixture.h"
#include "crankcheck/scene/scene_file.h"
#include "crankcheck/validation/balance.h"
#include "crankcheck/validation/csv.h"
#include "crankcheck/validation/table_schemas.h"
#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/report_part.h"
#include "crankcheck/validation/scales.h"

namespace crankcheck::validation::your_engine {
namespace {

using Real = boost::multiprecision::cpp_bin_float_50;

// An angle of the scene [rad] in 50 digits: the scenes state their angles in degrees, so one that is a whole 1/8
// degree is that many degrees exactly (pi / 180 in 50 digits), not the double nearest it; another as it is. So the
// orders that cancel by the layout cancel here to 50 digits, not to the doubles' 1e-16.
Real exactAngle(double radians) {
  const double degrees = degreesFromRadians(radians), eighths = std::round(degrees * 8.0);
  if (std::fabs(degrees * 8.0 - eighths) > 1e-6) return Real(radians);
  return Real(eighths) / 8 * boost::math::constants::pi<Real>() / 180;
}

// The independent model's shaking force (X, Y) and moment (X, Y, Z) about O at crank angle phi.
struct Shake {
  std::array<Real, 2> force{};
  std::array<Real, 3> moment{};
};

// Every moving mass's position [m] and every rod's angle [rad] at crank angle phi (cylinder j's own crank angle
// theta_j = phi + alpha_j, its axis e_j at gamma_j, its wrist pin on A = x_p e + delta n with sin(beta) =
// lambda sin(theta) - delta / l, the rod's centre at z_k from the wrist pin toward the crank pin, each throw's masses
// on its crank line, each shaft's mass at ratio phi + phase about its axis).
struct Configuration {
  std::vector<std::array<Real, 3>> points;
  std::vector<Real> rod_angles;
};
class IndependentModel {
 public:
  explicit IndependentModel(const Mechanism& m) : m_(m) {
    const int k = m.machine.cylinders;
    for (int j = 0; j < k; ++j) {
      masses_.insert(masses_.end(), {Real(m.piston.mass), Real(m.rod.mass), Real(m.crank.mass), Real(m.crank.counterweight_mass)});
      rod_inertias_.push_back(Real(m.rod.inertia_about_wrist_pin) - Real(m.rod.mass) * Real(m.rod.com_from_wrist_pin) * Real(m.rod.com_from_wrist_pin));
    }
    for (const BalanceShaftParams& b : m.balance_shafts) masses_.push_back(Real(b.mass));
  }

  Configuration at(const Real& phi) const {
    Configuration c;
    const Real r = m_.crank.radius, l = m_.rod.length, zk = m_.rod.com_from_wrist_pin;
    for (int j = 0; j < m_.machine.cylinders; ++j) {
      const Real gamma = exactAngle(getBankAngle(m_, j)), delta = getPinOffset(m_, j), z = getAxialPosition(m_, j);
      const Real theta = phi + exactAngle(m_.machine.crank_angles[j]);
      const Real ce = cos(gamma), se = sin(gamma);
      auto global = [&](const Real& u, const Real& v) { return std::array<Real, 3>{u * ce - v * se, u * se + v * ce, z}; };
      const Real sin_beta = r / l * sin(theta) - delta / l;
      const Real beta = asin(sin_beta);
      const Real xp = r * cos(theta) + l * cos(beta);
      const Real bx = r * cos(theta), by = r * sin(theta);
      const Real mu = zk / l;
      c.points.push_back(global(xp, delta));                                        // piston
      c.points.push_back(global(xp + mu * (bx - xp), delta + mu * (by - delta)));  // rod's centre
      const Real rs = m_.crank.com_radius, rp = m_.crank.counterweight_radius;
      c.points.push_back(global(rs * cos(theta), rs * sin(theta)));    // throw mass on the crank line
      c.points.push_back(global(-rp * cos(theta), -rp * sin(theta)));  // counterweight opposite
      c.rod_angles.push_back(gamma - beta);  // B - A = l (-cos beta e + sin beta n): the rod turns as -beta
    }
    for (const BalanceShaftParams& b : m_.balance_shafts) {
      const Real psi = Real(b.ratio) * phi + exactAngle(b.phase);
      c.points.push_back({Real(b.position[0]) + Real(b.radius) * cos(psi), Real(b.position[1]) + Real(b.radius) * sin(psi),
                          Real(b.position[2])});
    }
    return c;
  }

  // Accelerations omega^2 d2/dphi2 by the central second difference with step h: its error h^2 / 12 of the fourth
  // derivative (1e-26 of the scale), its rounding 4 eps_50 / h^2 (1e-25): both far below the 1e-6 compared.
  Shake shakingAt(const Real& phi) const {
    const Real h("1e-12"), w = m_.machine.speed;
    const Configuration a = at(phi - h), b = at(phi), c = at(phi + h);
    const Real to_acceleration = w * w / (h * h);
    Shake s;
    for (size_t i = 0; i < b.points.size(); ++i) {
      std::array<Real, 3> f;  // -m a
      for (int k = 0; k < 3; ++k) f[k] = -masses_[i] * (a.points[i][k] - 2 * b.points[i][k] + c.points[i][k]) * to_acceleration;
      const std::array<Real, 3>& p = b.points[i];
      s.force[0] += f[0];
      s.force[1] += f[1];
      s.moment[0] += p[1] * f[2] - p[2] * f[1];
      s.moment[1] += p[2] * f[0] - p[0] * f[2];
      s.moment[2] += p[0] * f[1] - p[1] * f[0];
    }
    for (size_t j = 0; j < b.rod_angles.size(); ++j)
      s.moment[2] -= rod_inertias_[j] * (a.rod_angles[j] - 2 * b.rod_angles[j] + c.rod_angles[j]) * to_acceleration;
    return s;
  }

 private:
  Mechanism m_;
  std::vector<Real> masses_, rod_inertias_;
};

// Harmonics 1..kTerms of the independent shaking by a DFT over kSamples angles: what folds onto them (orders above
// kSamples - kTerms = 48) is below lambda^48 of the primary (1e-25 at the scenes' lambda <= 0.3).
constexpr int kSamples = 96, kTerms = 48;
struct Harmonic {
  std::array<long double, 5> c{}, s{};  // F X, Y; M X, Y, Z
};
struct Spectrum {
  std::vector<Harmonic> h;  // index n = 0..kTerms (0: the mean, unused)
};
Spectrum calcSpectrum(const Mechanism& m) {
  const IndependentModel model(m);
  const Real pi = boost::math::constants::pi<Real>();
  std::vector<std::array<Real, 5>> values;
  for (int i = 0; i < kSamples; ++i) {
    const Shake s = model.shakingAt(2 * pi * i / kSamples);
    values.push_back({s.force[0], s.force[1], s.moment[0], s.moment[1], s.moment[2]});
  }
  Spectrum out;
  out.h.resize(kTerms + 1);
  for (int n = 1; n <= kTerms; ++n)
    for (int q = 0; q < 5; ++q) {
      Real c = 0, s = 0;
      for (int i = 0; i < kSamples; ++i) {
        const Real angle = 2 * pi * n * i / kSamples;
        c += values[i][q] * cos(angle);
        s += values[i][q] * sin(angle);
      }
      out.h[n].c[q] = static_cast<long double>(2 * c / kSamples);
      out.h[n].s[q] = static_cast<long double>(2 * s / kSamples);
    }
  return out;
}

// The largest |c cos t + s sin t| of a planar harmonic: the semi-major axis of its ellipse, from the 2 x 2 Gram matrix.
long double semiMajor(long double cx, long double cy, long double sx, long double sy) {
  const long double cc = cx * cx + cy * cy, ss = sx * sx + sy * sy, cs = cx * sx + cy * sy;
  return std::sqrt((cc + ss) / 2 + std::sqrt((cc - ss) * (cc - ss) / 4 + cs * cs));
}
long double forceAmplitude(const Harmonic& h) { return semiMajor(h.c[0], h.c[1], h.s[0], h.s[1]); }
long double momentAmplitude(const Harmonic& h, bool couple) {
  return couple ? semiMajor(h.c[2], h.c[3], h.s[2], h.s[3]) : std::hypot(h.c[4], h.s[4]);
}

// The signal rebuilt from its harmonics (a trigonometric interpolation of the samples) and its largest magnitude:
// a 0.05 degree grid, then golden-section search on the best cells to 1e-13 rad.
struct Maxima {
  long double force = 0, moment = 0;
};
Maxima calcMaxima(const Spectrum& sp, bool couple) {
  auto value = [&](long double phi, bool force) {
    std::array<long double, 5> v{};
    for (int n = 1; n <= kTerms; ++n)
      for (int q = 0; q < 5; ++q) v[q] += sp.h[n].c[q] * std::cos(n * phi) + sp.h[n].s[q] * std::sin(n * phi);
    if (force) return std::hypot(v[0], v[1]);
    return couple ? std::hypot(v[2], v[3]) : std::fabs(v[4]);
  };
  Maxima out;
  for (const bool force : {true, false}) {
    constexpr int kGrid = 7200;
    const long double step = 2 * M_PIl / kGrid;
    std::vector<long double> grid(kGrid);
    for (int i = 0; i < kGrid; ++i) grid[i] = value(i * step, force);
    std::vector<int> order(kGrid);
    for (int i = 0; i < kGrid; ++i) order[i] = i;
    std::partial_sort(order.begin(), order.begin() + 4, order.end(), [&](int a, int b) { return grid[a] > grid[b]; });
    long double best = grid[order[0]];
    for (int rank = 0; rank < 4; ++rank) {
      long double a = (order[rank] - 1) * step, b = (order[rank] + 1) * step;
      const long double g = (std::sqrt(5.0L) - 1) / 2;
      while (b - a > 1e-13L) {
        const long double x1 = b - g * (b - a), x2 = a + g * (b - a);
        if (value(x1, force) > value(x2, force)) b = x2;
        else a = x1;
      }
      best = std::max(best, value((a + b) / 2, force));
    }
    (force ? out.force : out.moment) = best;
  }
  return out;
}

const SceneTopic& balanceTopic() { return testing::findTopic("Balance"); }

// The topic's tables on m, and the scene facts its describe reads.
TableSet runTopic(const Mechanism& m, bool quick = false) { return testing::runTopic(balanceTopic(), m, quick); }

std::vector<std::map<std::string, std::string>> rowsOf(const TableSet& t, const std::string& name) {
  return readRecords(t, name);
}
double number(const std::map<std::string, std::string>& row, const std::string& column) {
  return std::stod(row.at(column));
}

int countExactEngines() {
  return static_cast<int>(std::count_if(listEngines().begin(), listEngines().end(), [](const Engine& e) { return e.gated; }));
}

// Checks the topic's tables of m (one variant: its shafts as given, or cleared) against the independent model:
// the closed form's harmonics 1..8 and every exact engine's DFT, the largest force and moment over the turn of the
// closed form and of every exact engine. Each within the gate's agreement rule, 64 eps x its scale x the
// conditioning of accelerations (scales.h): the closed form's coefficients and the engines' DFTs are exact to
// rounding, and a maximum refined to the angle tolerance (1e-10 rad) is off by f'' tol^2 / 2, far below rounding
// (the issue's acceptance, 1e-6 relative, is far looser). A value below 1e-9 of its scale is at rounding level.
void checkVariant(const TableSet& t, const Mechanism& variant, const std::string& scene) {
  SCOPED_TRACE(scene + " with " + std::to_string(variant.balance_shafts.size()) + " shafts");
  const double conditioning = calcScales(variant).acceleration_conditioning;
  auto agreement = [conditioning](double scale) { return kAgreementMultiple * kEps * scale * conditioning; };
  const bool couple = hasAxialPositions(variant);
  const Spectrum sp = calcSpectrum(variant);
  const std::string shafts = std::to_string(variant.balance_shafts.size());
  int harmonics = 0, maxima = 0;
  for (const auto& row : rowsOf(t, "your_engine_balance_harmonics")) {
    if (row.at("scene") != scene || row.at("shafts") != shafts || row.at("gated") != "1") continue;
    const int n = std::stoi(row.at("n"));
    const double force_scale = number(rowsOf(t, "your_engine_balance").front(), "force_scale");
    const double moment_scale = number(rowsOf(t, "your_engine_balance").front(), "moment_scale");
    const long double f = forceAmplitude(sp.h[n]), q = momentAmplitude(sp.h[n], couple);
    SCOPED_TRACE(row.at("source") + " " + row.at("engine") + " n = " + std::to_string(n));
    const double got_f = number(row, "force_amplitude"), got_q = number(row, "moment_amplitude");
    EXPECT_NEAR(got_f, static_cast<double>(f), agreement(force_scale));
    EXPECT_NEAR(got_q, static_cast<double>(q), agreement(moment_scale));
    // An order the closed form calls exactly zero is zero in the independent model too: to its rounding (the second
    // difference's 1e-25 of the scale, 1e-18 leaves room for the DFT's sums over 96 samples).
    if (row.at("force_exact_zero") == "1") {
      EXPECT_EQ(got_f, 0.0);
      EXPECT_LT(f, 1e-18L * force_scale);
    }
    if (row.at("moment_exact_zero") == "1") {
      EXPECT_EQ(got_q, 0.0);
      EXPECT_LT(q, 1e-18L * moment_scale);
    }
    ++harmonics;
  }
  EXPECT_EQ(harmonics, 8 * (1 + countExactEngines())) << "the closed form and every exact engine's DFT, orders 1..8";
  const Maxima expected = calcMaxima(sp, couple);
  for (const auto& row : rowsOf(t, "your_engine_balance")) {
    if (row.at("scene") != scene || row.at("shafts") != shafts || row.at("gated") != "1") continue;
    SCOPED_TRACE("max over the turn, " + row.at("engine"));
    const double force_scale = number(row, "force_scale"), moment_scale = number(row, "moment_scale");
    EXPECT_EQ(row.at("moment"), couple ? "couple X, Y" : "rocking Z");
    const double got_f = number(row, "max_force"), got_q = number(row, "max_moment");
    EXPECT_NEAR(got_f, static_cast<double>(expected.force), agreement(force_scale));
    EXPECT_NEAR(got_q, static_cast<double>(expected.moment), agreement(moment_scale));
    EXPECT_EQ(row.at("force_resolved"), expected.force > 1e-9L * force_scale ? "1" : "0");
    EXPECT_EQ(row.at("moment_resolved"), expected.moment > 1e-9L * moment_scale ? "1" : "0");
    ++maxima;
  }
  EXPECT_EQ(maxima, countExactEngines()) << "every exact engine: the closed forms and the references";
}

void checkScene(const Mechanism& m) {
  const TableSet t = runTopic(m);
  checkVariant(t, m, m.name);
  if (!m.balance_shafts.empty()) {
    Mechanism without = m;
    without.balance_shafts.clear();
    checkVariant(t, without, m.name);
  }
}

// The closed form's row of order n of `scene`'s variant with `shafts` shafts.
std::map<std::string, std::string> closedRow(const TableSet& t, const std::string& scene, int shafts, int n) {
  for (const auto& row : rowsOf(t, "your_engine_balance_harmonics"))
    if (row.at("scene") == scene && row.at("shafts") == std::to_string(shafts) && row.at("n") == std::to_string(n) &&
        row.at("source") == "closed form")
      return row;
  ADD_FAILURE() << "no closed-form row " << scene << " n = " << n;
  return {};
}

using testing::joinText;

const std::string kParts = R"(
[crank]
radius = 0.043
mass = 1.2
com_radius = 0.02
counterweight_mass = 0.8
counterweight_radius = 0.035
[rod]
length = 0.145
mass = 0.55
com_from_wrist_pin = 0.105
inertia_about_wrist_pin = 0.0072
[piston]
mass = 0.35
)";
const std::string kGas = R"(
[gas]
bore = 0.081
cycle_angle_deg = [0, 30, 180, 360, 540, 690]
pressure_pa = [4.0e6, 3.0e6, 0.3e6, 0.0, -0.02e6, 1.5e6]
)";

Mechanism vTwin() {
  // A 90 degree V-twin on one pin, banks at 135 and 45 degrees, firing at 45 and 315 degrees (its cylinders' outer
  // dead centres), with gas (the shaking does not see it), every cylinder in one plane: the rocking torque.
  return parseScene(R"([engine]
cycle = "four-stroke"
speed_rpm = 5000
[[cylinder]]
bank_angle_deg = 135.0
throw_angle_deg = 90.0
firing_angle_deg = 45.0
[[cylinder]]
bank_angle_deg = 45.0
throw_angle_deg = 90.0
firing_angle_deg = 315.0
)" + kParts + kGas, "v_twin");
}

Mechanism offsetSingleWithShafts() {
  // A standing single with a pin offset and gas, and the pair of shafts (ratios 1 and -1) that cancels its primary
  // force (designBalanceShafts, balance.h): a primary balancer.
  Mechanism m = parseScene(R"([engine]
cylinders = 1
cycle = "four-stroke"
cylinder_angle_deg = 90
speed_rpm = 4000
pin_offset = -0.001
)" + kParts + kGas + "firing_order = [0]\n", "offset_single");
  m.balance_shafts = designBalanceShafts(m, 1);
  return m;
}

Mechanism inline3() {
  // A two-stroke inline three standing, cylinders 0.09 m apart: no primary or secondary force, a rocking couple.
  return parseScene(R"([engine]
cylinders = 3
cycle = "two-stroke"
cylinder_angle_deg = 90
cylinder_spacing = 0.09
speed_rpm = 6000
)" + kParts, "inline3");
}

Mechanism inline4() {
  // A bare four-stroke inline four standing (no gas, flywheel, crankshaft or axial positions): the secondary force.
  return parseScene(R"([engine]
cylinders = 4
cycle = "four-stroke"
cylinder_angle_deg = 90
speed_rpm = 6000
)" + kParts, "inline4");
}

TEST(YourEngineBalanceTest, VTwinAgreesWithTheIndependentModel) { checkScene(vTwin()); }

TEST(YourEngineBalanceTest, OffsetSingleWithPrimaryShaftsAgreesWithAndWithout) {
  const Mechanism m = offsetSingleWithShafts();
  ASSERT_EQ(m.balance_shafts.size(), 2u);
  checkScene(m);
  // The shafts cancel the primary force: with them it is rounding of the force scale, without them the independent
  // model's primary.
  const TableSet t = runTopic(m);
  const double scale = calcScales(m).force;
  EXPECT_LT(std::stod(closedRow(t, m.name, 2, 1).at("force_amplitude")), 1e-12 * scale);
  Mechanism without = m;
  without.balance_shafts.clear();
  const long double primary = forceAmplitude(calcSpectrum(without).h[1]);
  // The agreement rule, as checkVariant: the closed form's primary without its shafts is exact to rounding.
  EXPECT_NEAR(std::stod(closedRow(t, m.name, 0, 1).at("force_amplitude")), static_cast<double>(primary),
              kAgreementMultiple * kEps * calcScales(without).force * calcScales(without).acceleration_conditioning);
  const std::string text = joinText(balanceTopic().describe(t, m.name));
  EXPECT_NE(text.find("Without its 2 balance shafts"), std::string::npos) << text;
  EXPECT_NE(text.find("force without shafts [N]"), std::string::npos) << text;
}

TEST(YourEngineBalanceTest, Inline3HasNoPrimaryOrSecondaryForceButACouple) {
  const Mechanism m = inline3();
  checkScene(m);
  const TableSet t = runTopic(m);
  for (int n : {1, 2}) {
    const auto row = closedRow(t, m.name, 0, n);
    EXPECT_EQ(row.at("force_exact_zero"), "1") << n;
    EXPECT_EQ(row.at("moment_exact_zero"), "0") << n;
    EXPECT_GT(std::stod(row.at("moment_amplitude")), 0.0) << n;
  }
  const std::string text = joinText(balanceTopic().describe(t, m.name));
  EXPECT_NE(text.find("couple X, Y [N m]"), std::string::npos) << text;
  EXPECT_NE(text.find("0 (exact)"), std::string::npos) << text;
  EXPECT_NE(text.find("no [[balance_shaft]]"), std::string::npos) << text;
}

TEST(YourEngineBalanceTest, Inline4HasASecondaryForceAndNoRockingTorque) {
  const Mechanism m = inline4();
  checkScene(m);
  const TableSet t = runTopic(m);
  EXPECT_EQ(closedRow(t, m.name, 0, 1).at("force_exact_zero"), "1");
  EXPECT_EQ(closedRow(t, m.name, 0, 2).at("force_exact_zero"), "0");
  for (int n = 1; n <= 8; ++n) EXPECT_EQ(closedRow(t, m.name, 0, n).at("moment_exact_zero"), "1") << n;
  const std::string text = joinText(balanceTopic().describe(t, m.name));
  EXPECT_NE(text.find("rocking Z [N m]"), std::string::npos) << text;
  EXPECT_NE(text.find("0 to rounding"), std::string::npos) << text;  // the rocking torque's maximum
}

TEST(YourEngineBalanceTest, ExampleScenesAgreeWithTheIndependentModel) {
  for (const std::string stem : {"v8_cross_plane", "inline4_pin_offset", "single_cylinder"})
    checkScene(loadSceneFile(std::string(CRANKCHECK_SCENES_DIR) + "/" + stem + ".toml"));
}

TEST(YourEngineBalanceTest, QuickCampaignGivesTheSameMaxima) {
  const Mechanism m = vTwin();
  const TableSet full = runTopic(m), quick = runTopic(m, true);
  const auto a = rowsOf(full, "your_engine_balance"), b = rowsOf(quick, "your_engine_balance");
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    for (const std::string c : {"max_force", "max_moment"})
      EXPECT_NEAR(number(a[i], c), number(b[i], c), 0.01 * number(a[i], c)) << a[i].at("engine") << " " << c;
}

TEST(YourEngineBalanceTest, SceneAtRestSaysSo) {
  Mechanism m = inline4();
  m.machine.speed = 0.0;
  m.speed_rpm = 0.0;
  const std::vector<ReportBlock> blocks = balanceTopic().describe(runTopic(m), m.name);
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_NE(blocks[0].text.find("No speed"), std::string::npos) << blocks[0].text;
  EXPECT_NE(blocks[0].text.find("docs/SCENE-FORMAT.md"), std::string::npos) << blocks[0].text;
}

TEST(YourEngineBalanceTest, NothingWithoutItsTables) {
  EXPECT_TRUE(balanceTopic().describe(TableSet{}, "inline4").empty());
}

TEST(YourEngineBalanceTest, TablesReadBackThroughTheirSchemas) {
  const TableSet t = runTopic(offsetSingleWithShafts());
  for (const TableSchema* schema : balanceTopic().schemas()) {
    ASSERT_TRUE(t.count(schema->name())) << schema->name();
    const std::string csv = formatCsv(t.at(schema->name()));
    const Table back = parseTable(schema->name(), parseCsv(csv, schema->name()), schema->name(), findTableSchema(schema->name()));
    EXPECT_EQ(formatCsv(back), csv) << schema->name();
  }
}

}  // namespace
}  // namespace crankcheck::validation::your_engine
