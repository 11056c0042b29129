#include "crankcheck/scene/scene_file.h"

#include <charconv>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <cstdint>
#include <sstream>
#include <utility>
#include <toml++/toml.h>

#include "crankcheck/scene/text.h"

namespace crankcheck {
namespace {

// The limits on scene and mechanism values, one per unit, each with its reason (docs/SCENE-FORMAT.md, "Limits",
// states the same table). `text` is how a refusal names the limit. validateMechanism applies them, so a scene and a
// programmatically built Mechanism obey the same rules; the reader only checks angles in degrees (as typed) as well.
struct Limit {
  double value;
  const char* text;
};
// Lengths [m]: 1000 km is beyond any machine; the tiny-lambda stress case lambda = 1e-6 on a 0.2 m crank needs 2e5 m.
constexpr Limit kMaxLength{1e6, "1e6 m (1000 km)"};
// Positive lengths (r, l) [m]: below a micrometre there is no machine, and scales built from r^2 and r^3 would
// approach the bottom of double's normal range when combined with tiny masses.
constexpr Limit kMinPositiveLength{1e-6, "1e-6 m (a micrometre)"};
// Masses [kg]: 1000 t is beyond the heaviest marine crank train per cylinder.
constexpr Limit kMaxMass{1e6, "1e6 kg (1000 t)"};
// Nonzero masses [kg]: below a microgram there is no real part, and every force scale would underflow relative to
// the rounding of the weights. Exactly 0 stays accepted (a massless part is a real modelling choice).
constexpr Limit kMinNonzeroMass{1e-9, "1e-9 kg (a microgram)"};
// Inertias [kg m^2]: the largest accepted mass on the longest accepted length, 1e6 kg x (1e6 m)^2.
constexpr Limit kMaxInertia{kMaxMass.value * kMaxLength.value * kMaxLength.value, "1e18 kg m^2 (1e6 kg at 1e6 m)"};
// Speed [rpm]: four orders above the fastest reciprocating machines; keeps omega^2 r and the inertia forces
// m omega^2 r of the largest accepted machine far inside double's range: 1e6 kg x (1.05e5 rad/s)^2 x 1e6 m = 1e22 N.
constexpr Limit kMaxSpeedRpm{1e6, "1e6 rpm"};
// The least speed but 0: one turn in about two years. Below it omega^2 underflows in the loads (5e-324 rpm is an
// omega of 0 in double), so a nonzero speed below it is no speed any command could compute at.
constexpr Limit kMinNonzeroSpeedRpm{1e-6, "1e-6 rpm"};
// Gravity [m/s^2]: 1e5 g, beyond any centrifuge test rig.
constexpr Limit kMaxGravity{1e6, "1e6 m/s^2 (1e5 g)"};
// Angles [deg], in magnitude: at 1e6 deg the spacing of doubles is 1.2e-10 deg, so the angle still means what was
// typed to better than 1e-9 deg; larger values lose the fraction of a degree.
constexpr Limit kMaxAngleDeg{1e6, "1e6 deg"};
// Gas pressure [Pa], gauge: at least -101325 Pa (below that there is no pressure at all) and at most 1e9 Pa (10 kbar,
// four times the peak of the most highly charged diesels).
constexpr Limit kMinGaugePressure{-101325.0, "-101325 Pa (no pressure at all)"};
constexpr Limit kMaxGaugePressure{1e9, "1e9 Pa (10 kbar)"};
// Torsional stiffness [N m/rad] and damping [N m s/rad] of the crank train: at most 1e18, eight orders above the
// stiffest section of a ship's crankshaft (about 1e10 N m/rad); with inertias of at most 1e18 kg m^2 the products
// K x, C omega and omega^2 J of the torsion analysis stay far inside double's range.
constexpr Limit kMaxStiffness{1e18, "1e18 N m/rad"};
constexpr Limit kMaxDamping{1e18, "1e18 N m s/rad"};
// Cylinders: 1..64, more than any engine built; keeps the per-cylinder work and output bounded.
constexpr int kMaxCylinders = 64;
static_assert(kMaxInertia.value == 1e18);

// x in its shortest form that reads back to the same double (0.1, not 0.10000000000000001), for messages.
std::string formatNumber(double x) {
  char buffer[40];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, x).ptr);
}

// The source and the key are the user's text (a quoted TOML key may hold a NUL or an escape sequence): shown with
// their control characters escaped, so that the message is one line that cannot act on a terminal.
[[noreturn]] void fail(const std::string& source, const std::string& key, const std::string& rule) {
  throw SceneError(escapeControls(source) + ": " + escapeControls(key) + ": " + rule);
}

// A TOML integer given for a number key, as a double. Beyond 2^53 a double cannot hold every integer, and the nearest
// one may lie on the other side of a limit: 1000000000000000001 rounds to 1e18, the limit of the inertias, stiffness
// and damping. The double next to the integer away from zero is taken instead (|x| >= |i|, at most one ulp more), so
// that every limit, itself a double, compares with the value as typed: 1000000000000000001 is above 1e18.
// The integers of the scene being parsed that numberFromInteger moved (the double taken, the integer typed), so that
// a limit's refusal quotes the value as typed ("(got 1000000000000000001)"), not the double beside it. One list per
// parseScene on its thread (InexactIntegers); none outside a parse.
thread_local std::vector<std::pair<double, long long>>* inexact_integers = nullptr;

double numberFromInteger(long long i) {
  double x = static_cast<double>(i);
  // i near 2^63 rounds up to 2^63: already away from zero, and beyond long long (no cast back)
  bool exact = false;
  if (x < 0x1p63) {
    const long long back = static_cast<long long>(x);
    exact = back == i;
    if (i > 0 && back < i) x = std::nextafter(x, HUGE_VAL);
    if (i < 0 && back > i) x = std::nextafter(x, -HUGE_VAL);
  }
  if (!exact && inexact_integers != nullptr) inexact_integers->emplace_back(x, i);
  return x;
}

// The list of numberFromInteger's moved integers for one parse (the scope of inexact_integers).
class InexactIntegers {
 public:
  InexactIntegers() : previous_(inexact_integers) { inexact_integers = &moved_; }
  ~InexactIntegers() { inexact_integers = previous_; }
  InexactIntegers(const InexactIntegers&) = delete;
  InexactIntegers& operator=(const InexactIntegers&) = delete;
  /// `message` with a moved integer's double, where it is quoted as "(got X)", shown as the integer typed.
  std::string quoteAsTyped(std::string message) const {
    for (const auto& [x, typed] : moved_) {
      const std::string shown = "(got " + formatNumber(x) + ")";
      if (const size_t at = message.rfind(shown); at != std::string::npos)
        return message.replace(at, shown.size(), "(got " + std::to_string(typed) + ")");
    }
    return message;
  }

 private:
  std::vector<std::pair<double, long long>> moved_;
  std::vector<std::pair<double, long long>>* previous_;
};

// What a value of the wrong type is, for a refusal's "(got ...)": a string as typed (quoted, its control characters
// escaped, cut at 40 characters), a boolean, or the kind of value ("an array", "a table", "a date").
std::string describeNode(const toml::node& node) {
  if (const toml::value<std::string>* text = node.as_string()) {
    const std::string& value = text->get();
    return value.size() <= 40 ? quoteText(value) : quoteText(value.substr(0, 40)) + "...";
  }
  if (const toml::value<bool>* flag = node.as_boolean()) return flag->get() ? "true" : "false";
  if (node.is_array()) return "an array";
  if (node.is_table()) return "a table";
  if (node.is_integer()) return "an integer";
  if (node.is_floating_point()) return "a number";
  return "a date or time";
}

// The value of an integer key (format_version, [engine].cylinders, each index of [gas].firing_order): a TOML integer,
// or a float whose value is an exact integer, 4.0 being 4 (the JSON Schema that editors check scenes with cannot tell
// 4.0 from 4, so neither does crankcheck). Refused, naming the key: any other type ("must be an integer"); a float
// with a fraction, NaN or infinity ("must be an integer (got 4.5)"); a value outside lo..hi, with the key's own rule
// outside(above, got), `above` telling which side and `got` the value as typed (a float in its shortest form), so
// that 65 and 65.0 (and 1e300, beyond every 64-bit integer) get the same message. Every integer key is read here.
template <typename Outside>
long long integerValue(const toml::node& node, const std::string& source, const std::string& key, int lo, int hi,
                       const Outside& outside) {
  if (const toml::value<int64_t>* integer = node.as_integer()) {
    const long long v = integer->get();
    if (v < lo || v > hi) fail(source, key, outside(v > hi, std::to_string(v)));
    return v;
  }
  if (const toml::value<double>* floating = node.as_floating_point()) {
    const double x = floating->get();
    if (!std::isfinite(x) || x != std::trunc(x)) fail(source, key, "must be an integer (got " + formatNumber(x) + ")");
    // lo and hi are ints, exact as doubles: x within them converts to long long exactly.
    if (x < lo || x > hi) fail(source, key, outside(x > hi, formatNumber(x == 0.0 ? 0.0 : x)));  // -0 as 0
    return static_cast<long long>(x);
  }
  fail(source, key, "must be an integer (got " + describeNode(node) + ")");
}

// Reads one table of the scene, keeping track of which keys were used so that unknown keys are refused.
class TableReader {
 public:
  // Refuses unknown keys first, so that a misspelt key is reported as such, not as a missing one.
  TableReader(const toml::table& root, std::string name, std::string source, bool required,
              std::set<std::string> allowed)
      : prefix_("[" + name + "]"), source_(std::move(source)), allowed_(std::move(allowed)) {
    const toml::node* node = root.get(name);
    if (node == nullptr) {
      if (required) fail(source_, prefix_, "missing table");
      return;
    }
    table_ = node->as_table();
    if (table_ == nullptr) fail(source_, prefix_, "must be a table (got " + describeNode(*node) + ")");
    refuseUnknownKeys();
  }

  // One table of an array of tables, named in messages as `prefix` (e.g. "cylinder[2]").
  TableReader(const toml::table& table, std::string prefix, std::string source, std::set<std::string> allowed)
      : prefix_(std::move(prefix)), source_(std::move(source)), allowed_(std::move(allowed)), table_(&table) {
    refuseUnknownKeys();
  }

  bool present() const { return table_ != nullptr; }
  std::string key(const std::string& k) const { return prefix_ + "." + k; }

  const toml::node* find(const std::string& k) {
    if (!allowed_.contains(k)) throw std::logic_error("scene reader: key not in the allowed list: " + k);
    return table_ == nullptr ? nullptr : table_->get(k);
  }

  double number(const std::string& k, std::optional<double> fallback = std::nullopt) {
    const toml::node* node = find(k);
    if (node == nullptr) {
      if (fallback) return *fallback;
      fail(source_, key(k), "missing key");
    }
    return toNumber(*node, key(k));
  }

  std::optional<double> optionalNumber(const std::string& k) {
    const toml::node* node = find(k);
    if (node == nullptr) return std::nullopt;
    return toNumber(*node, key(k));
  }

  // An integer key within lo..hi (integerValue).
  template <typename Outside>
  long long integer(const std::string& k, int lo, int hi, const Outside& outside) {
    const toml::node* node = find(k);
    if (node == nullptr) fail(source_, key(k), "missing key");
    return integerValue(*node, source_, key(k), lo, hi, outside);
  }

  std::string string(const std::string& k, std::optional<std::string> fallback = std::nullopt) {
    const toml::node* node = find(k);
    if (node == nullptr) {
      if (fallback) return *fallback;
      fail(source_, key(k), "missing key");
    }
    if (!node->is_string()) fail(source_, key(k), "must be a string (got " + describeNode(*node) + ")");
    return node->as_string()->get();
  }

  std::optional<std::vector<double>> optionalNumberArray(const std::string& k) {
    const toml::node* node = find(k);
    if (node == nullptr) return std::nullopt;
    const toml::array* array = node->as_array();
    if (array == nullptr) fail(source_, key(k), "must be an array of numbers (got " + describeNode(*node) + ")");
    std::vector<double> values;
    for (size_t i = 0; i < array->size(); ++i)
      values.push_back(toNumber(*array->get(i), key(k) + "[" + std::to_string(i) + "]"));
    return values;
  }

 private:
  double toNumber(const toml::node& node, const std::string& key_name) const {
    double x = 0.0;
    if (node.is_floating_point()) {
      x = node.as_floating_point()->get();
    } else if (node.is_integer()) {
      x = numberFromInteger(node.as_integer()->get());
    } else {
      fail(source_, key_name, "must be a number (got " + describeNode(node) + ")");
    }
    if (!std::isfinite(x)) fail(source_, key_name, "must be finite (got " + formatNumber(x) + ")");
    return x;  // each unit's limits: validateMechanism (angles in degrees also: requireAngleDegrees)
  }

  void refuseUnknownKeys() const {
    for (const auto& [k, v] : *table_) {
      const std::string key_name(k.str());
      if (!allowed_.contains(key_name)) {
        std::string list;
        for (const std::string& a : allowed_) list += (list.empty() ? "" : ", ") + a;
        fail(source_, key(key_name), "unknown key (allowed: " + list + ")");
      }
    }
  }

  std::string prefix_;
  std::string source_;
  std::set<std::string> allowed_;
  const toml::table* table_ = nullptr;
};

// Refuses an angle typed in degrees beyond kMaxAngleDeg, before it is converted, so the message shows it as typed.
void requireAngleDegrees(double degrees, const std::string& source, const std::string& key) {
  if (std::fabs(degrees) > kMaxAngleDeg.value)
    fail(source, key, std::string("magnitude must be at most ") + kMaxAngleDeg.text + " (got " + formatNumber(degrees) +
                          ")");
}

}  // namespace

void validateMechanism(const Mechanism& m, const std::string& source) {
  auto require = [&](bool ok, const std::string& key, const std::string& rule, double got) {
    if (!ok) fail(source, key, rule + " (got " + formatNumber(got) + ")");
  };
  const auto finite = [](double x) { return std::isfinite(x); };
  const auto atMost = [](const Limit& limit) { return std::string("must be at most ") + limit.text; };
  const auto requireFinite = [&](double x, const std::string& key) { require(finite(x), key, "must be finite", x); };
  // Lengths that may be 0 (a point at the centre) and lengths that must be positive.
  const auto requireLength = [&](double x, const std::string& key) {
    requireFinite(x, key);
    require(x >= 0, key, "must be >= 0", x);
    require(x <= kMaxLength.value, key, atMost(kMaxLength), x);
  };
  const auto requirePositiveLength = [&](double x, const std::string& key) {
    requireFinite(x, key);
    require(x >= kMinPositiveLength.value, key, std::string("must be at least ") + kMinPositiveLength.text, x);
    require(x <= kMaxLength.value, key, atMost(kMaxLength), x);
  };
  const auto requireMass = [&](double x, const std::string& key) {
    requireFinite(x, key);
    require(x >= 0, key, "must be >= 0", x);
    require(x == 0 || x >= kMinNonzeroMass.value, key, std::string("must be 0 or at least ") + kMinNonzeroMass.text, x);
    require(x <= kMaxMass.value, key, atMost(kMaxMass), x);
  };
  const auto requireAngle = [&](double radians, const std::string& key) {
    requireFinite(radians, key);
    // The same limit in radians; a scene's angles were already checked in degrees as typed (requireAngleDegrees).
    require(std::fabs(radians) <= radiansFromDegrees(kMaxAngleDeg.value), key,
            std::string("magnitude must be at most ") + kMaxAngleDeg.text, degreesFromRadians(radians));
  };

  require(m.machine.cylinders >= 1 && m.machine.cylinders <= kMaxCylinders, "[engine].cylinders",
          "must be between 1 and 64", m.machine.cylinders);
  require(static_cast<int>(m.machine.crank_angles.size()) == m.machine.cylinders, "[engine].crank_angles_deg",
          "must have one angle per cylinder", static_cast<double>(m.machine.crank_angles.size()));
  // A layout's alpha_j is its throw angle minus its bank angle: name the cylinder, not a key it does not have.
  for (size_t i = 0; i < m.machine.crank_angles.size(); ++i)
    requireAngle(m.machine.crank_angles[i],
                 m.machine.bank_angles.empty()
                     ? "[engine].crank_angles_deg[" + std::to_string(i) + "]"
                     : "cylinder[" + std::to_string(i) + "] (throw_angle_deg - bank_angle_deg)");
  requireAngle(m.machine.cylinder_angle, "[engine].cylinder_angle_deg");
  const size_t k = static_cast<size_t>(std::max(m.machine.cylinders, 0));
  require(m.machine.bank_angles.empty() || m.machine.bank_angles.size() == k, "[[cylinder]]",
          "must give every cylinder a bank angle", static_cast<double>(m.machine.bank_angles.size()));
  for (size_t i = 0; i < m.machine.bank_angles.size(); ++i)
    requireAngle(m.machine.bank_angles[i], "cylinder[" + std::to_string(i) + "].bank_angle_deg");
  require(m.machine.axial_positions.empty() || m.machine.axial_positions.size() == k, "[[cylinder]]",
          "must give every cylinder an axial position", static_cast<double>(m.machine.axial_positions.size()));
  for (size_t i = 0; i < m.machine.axial_positions.size(); ++i) {
    const std::string key = "cylinder[" + std::to_string(i) + "].axial_position";
    requireFinite(m.machine.axial_positions[i], key);
    require(std::fabs(m.machine.axial_positions[i]) <= kMaxLength.value, key,
            "magnitude " + atMost(kMaxLength), m.machine.axial_positions[i]);
  }
  // The speed is checked in rpm, the unit of the limit: the scene's value as typed when it is the one omega came
  // from, else omega converted.
  const double rpm = m.speed_rpm * (M_PI / 30.0) == m.machine.speed ? m.speed_rpm : m.machine.speed * (30.0 / M_PI);
  require(finite(m.machine.speed), "[engine].speed_rpm", "must be finite", rpm);
  require(rpm >= 0, "[engine].speed_rpm", "must be >= 0", rpm);
  require(rpm == 0 || rpm >= kMinNonzeroSpeedRpm.value, "[engine].speed_rpm",
          std::string("must be 0 (static) or at least ") + kMinNonzeroSpeedRpm.text, rpm);
  require(rpm <= kMaxSpeedRpm.value, "[engine].speed_rpm", atMost(kMaxSpeedRpm), rpm);
  requireFinite(m.machine.gravity, "[engine].gravity");
  require(m.machine.gravity >= 0, "[engine].gravity", "must be >= 0", m.machine.gravity);
  require(m.machine.gravity <= kMaxGravity.value, "[engine].gravity", atMost(kMaxGravity), m.machine.gravity);

  requirePositiveLength(m.crank.radius, "[crank].radius");
  requireMass(m.crank.mass, "[crank].mass");
  requireLength(m.crank.com_radius, "[crank].com_radius");
  requireMass(m.crank.counterweight_mass, "[crank].counterweight_mass");
  requireLength(m.crank.counterweight_radius, "[crank].counterweight_radius");

  requirePositiveLength(m.rod.length, "[rod].length");
  require(m.crank.radius < m.rod.length, "[crank].radius",
          "lambda = r / l must be < 1 (rod length " + formatNumber(m.rod.length) + " m)",
          m.crank.radius / m.rod.length);
  require(m.balance_shafts.size() <= static_cast<size_t>(kMaxCylinders), "[[balance_shaft]]", "must be at most 64 shafts",
          static_cast<double>(m.balance_shafts.size()));
  for (size_t i = 0; i < m.balance_shafts.size(); ++i) {
    const BalanceShaftParams& b = m.balance_shafts[i];
    const std::string key = "balance_shaft[" + std::to_string(i) + "]";
    requireFinite(b.ratio, key + ".ratio");
    require(b.ratio != 0.0 && std::fabs(b.ratio) <= kMaxCylinders, key + ".ratio",
            "must be nonzero and at most 64 in magnitude (shaft turns per crank turn)", b.ratio);
    // A whole number: the shaft's motion then repeats with every crank turn, as the harmonics (order n of the
    // turn), the energy integrals and the free run over a cycle assume; 1.5 would need two crank turns.
    require(b.ratio == std::round(b.ratio), key + ".ratio",
            "must be a whole number of shaft turns per crank turn (e.g. 1, -1, 2, -2), so that the mechanism repeats "
            "every crank turn",
            b.ratio);
    requireFinite(b.mass, key + ".mass");
    require(b.mass > 0.0, key + ".mass", "must be > 0 (a shaft without a mass balances nothing)", b.mass);
    require(b.mass >= kMinNonzeroMass.value, key + ".mass", std::string("must be at least ") + kMinNonzeroMass.text,
            b.mass);
    require(b.mass <= kMaxMass.value, key + ".mass", atMost(kMaxMass), b.mass);
    requirePositiveLength(b.radius, key + ".radius");
    requireAngle(b.phase, key + ".phase_deg");
    for (int c = 0; c < 3; ++c) {
      const std::string pkey = key + ".position[" + std::to_string(c) + "]";
      requireFinite(b.position[static_cast<size_t>(c)], pkey);
      require(std::fabs(b.position[static_cast<size_t>(c)]) <= kMaxLength.value, pkey, "magnitude " + atMost(kMaxLength),
              b.position[static_cast<size_t>(c)]);
    }
  }
  // The pin offset: the rod reaches the crank pin at every angle only if |delta| + r < l.
  require(m.machine.pin_offsets.empty() || m.machine.pin_offsets.size() == k, "[[cylinder]]",
          "must give every cylinder a pin offset", static_cast<double>(m.machine.pin_offsets.size()));
  for (size_t i = 0; i < m.machine.pin_offsets.size(); ++i) {
    const std::string key = m.machine.bank_angles.empty() ? "[engine].pin_offset" : "cylinder[" + std::to_string(i) + "].pin_offset";
    const double delta = m.machine.pin_offsets[i];
    requireFinite(delta, key);
    require(std::fabs(delta) < m.rod.length - m.crank.radius, key,
            "|pin_offset| must be < l - r = " + formatNumber(m.rod.length - m.crank.radius) +
                " m (beyond it the rod cannot reach the crank pin at every angle: no mechanism)",
            delta);
  }
  requireMass(m.rod.mass, "[rod].mass");
  require(finite(m.rod.com_from_wrist_pin) && m.rod.com_from_wrist_pin >= 0 &&
              m.rod.com_from_wrist_pin <= m.rod.length,
          "[rod].com_from_wrist_pin", "must lie on the rod, 0 <= z_k <= l", m.rod.com_from_wrist_pin);
  const double inertia_of_point_mass = m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  requireFinite(m.rod.inertia_about_wrist_pin, "[rod].inertia_about_wrist_pin");
  require(m.rod.inertia_about_wrist_pin <= kMaxInertia.value, "[rod].inertia_about_wrist_pin", atMost(kMaxInertia),
          m.rod.inertia_about_wrist_pin);
  require(m.rod.inertia_about_wrist_pin >= inertia_of_point_mass, "[rod].inertia_about_wrist_pin",
          "must be >= m_k z_k^2 = " + formatNumber(inertia_of_point_mass) + " kg m^2",
          m.rod.inertia_about_wrist_pin);

  requireMass(m.piston.mass, "[piston].mass");
  if (m.gas) {
    const GasParams& g = *m.gas;
    requirePositiveLength(g.bore, "[gas].bore");
    require(m.machine.acting == Acting::kSingle, "[gas]", "is modelled for single-acting cylinders only",
            m.machine.acting == Acting::kSingle ? 1.0 : 2.0);
    require(!g.cycle_angles.empty() && g.cycle_angles.size() == g.pressures.size(), "[gas].pressure_pa",
            "must have one pressure per cycle angle", static_cast<double>(g.pressures.size()));
    for (size_t i = 0; i < g.pressures.size(); ++i) {
      const std::string key = "[gas].pressure_pa[" + std::to_string(i) + "]";
      requireFinite(g.pressures[i], key);
      require(g.pressures[i] >= kMinGaugePressure.value, key, std::string("must be at least ") + kMinGaugePressure.text,
              g.pressures[i]);
      require(g.pressures[i] <= kMaxGaugePressure.value, key, atMost(kMaxGaugePressure), g.pressures[i]);
    }
    require(m.firing_angles.size() == k, "[gas]", "needs a firing angle for every cylinder",
            static_cast<double>(m.firing_angles.size()));
    for (size_t i = 0; i < m.firing_angles.size() && i < m.machine.crank_angles.size(); ++i) {
      // At its firing angle the cylinder must be at its outer dead centre: theta = firing + alpha_j = 0 (mod 360).
      const double theta = std::remainder(m.firing_angles[i] + m.machine.crank_angles[i], 2.0 * M_PI);
      // Where it is: phi = -alpha_j (mod 360), and 360 deg later too in a four-stroke cycle.
      const double odc = std::fmod(std::fmod(-degreesFromRadians(m.machine.crank_angles[i]), 360.0) + 360.0, 360.0);
      const std::string valid = m.machine.cycle == Cycle::kFourStroke
                                    ? formatNumber(odc) + " or " + formatNumber(odc + 360.0) + " deg"
                                    : formatNumber(odc) + " deg";
      require(std::fabs(theta) <= 1e-9,
              m.machine.bank_angles.empty() ? "[gas].firing_order" : "cylinder[" + std::to_string(i) + "].firing_angle_deg",
              "cylinder " + std::to_string(i) + " is not at its outer dead centre at its firing angle (its own crank angle theta is " +
                  formatNumber(degreesFromRadians(theta)) + " deg); it is there at phi = " + valid,
              degreesFromRadians(m.firing_angles[i]));
    }
  }
  if (m.crankshaft) {
    // The elastic crank train (docs/CONVENTIONS.md, "The elastic crank train"): one stiffness per section (a front mass adds
    // one); damping one value for all sections or one each. A scene's [crankshaft] also needs a speed (parseScene:
    // a mechanism derived at rest for the rigid engines keeps its table).
    const CrankshaftParams& c = *m.crankshaft;
    for (const auto& [x, key] : {std::pair{c.throw_inertia, "[crankshaft].throw_inertia"},
                                 std::pair{c.front_inertia, "[crankshaft].front_inertia"}}) {
      requireFinite(x, key);
      require(x >= 0.0, key, "must be >= 0", x);
      require(x <= kMaxInertia.value, key, atMost(kMaxInertia), x);
    }
    const size_t throws = findThrows(m).size();
    const size_t sections = static_cast<size_t>(countShaftSections(m));
    require(c.stiffness.size() == sections, "[crankshaft].stiffness",
            "must have " + std::to_string(sections) + (sections == 1 ? " value" : " values") +
                ", one per section from front to flywheel (" +
                std::to_string(throws) + (throws == 1 ? " throw" : " throws") +
                (c.front_inertia > 0.0 ? " and a front mass: throws + 1" : ", no front mass: one per throw") + ")",
            static_cast<double>(c.stiffness.size()));
    for (size_t i = 0; i < c.stiffness.size(); ++i) {
      const std::string key = "[crankshaft].stiffness[" + std::to_string(i) + "]";
      requireFinite(c.stiffness[i], key);
      require(c.stiffness[i] > 0.0, key, "must be > 0", c.stiffness[i]);
      require(c.stiffness[i] <= kMaxStiffness.value, key, atMost(kMaxStiffness), c.stiffness[i]);
    }
    require(c.section_damping.size() == 1 || c.section_damping.size() == sections, "[crankshaft].section_damping",
            "must be one value for all sections, or a list of " + std::to_string(sections) + " (one per section)",
            static_cast<double>(c.section_damping.size()));
    for (size_t i = 0; i < c.section_damping.size(); ++i) {
      const std::string key =
          "[crankshaft].section_damping" + (c.section_damping.size() == 1 ? std::string() : "[" + std::to_string(i) + "]");
      requireFinite(c.section_damping[i], key);
      require(c.section_damping[i] >= 0.0, key, "must be >= 0", c.section_damping[i]);
      require(c.section_damping[i] <= kMaxDamping.value, key, atMost(kMaxDamping), c.section_damping[i]);
    }
    requireFinite(c.throw_damping, "[crankshaft].throw_damping");
    require(c.throw_damping >= 0.0, "[crankshaft].throw_damping", "must be >= 0", c.throw_damping);
    require(c.throw_damping <= kMaxDamping.value, "[crankshaft].throw_damping", atMost(kMaxDamping), c.throw_damping);
  }
  if (m.flywheel_inertia) {
    requireFinite(*m.flywheel_inertia, "[flywheel].inertia");
    require(*m.flywheel_inertia > 0, "[flywheel].inertia", "must be > 0", *m.flywheel_inertia);
    require(*m.flywheel_inertia <= kMaxInertia.value, "[flywheel].inertia", atMost(kMaxInertia), *m.flywheel_inertia);
  }
}

Mechanism parseScene(std::string_view text, const std::string& source) {
  const InexactIntegers moved_integers;
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    fail(source, "line " + std::to_string(where.line) + ", column " + std::to_string(where.column),
         "not valid TOML: " + std::string(e.description()));
  }
  // format_version first: a scene written for a newer format is refused as such, not by the first key it added.
  if (const toml::node* version = root.get("format_version")) {
    integerValue(*version, source, "format_version", 1, kSceneFormatVersion, [](bool above, const std::string& got) {
      return above ? "scene format " + got + " is newer than this crankcheck reads (format " +
                         std::to_string(kSceneFormatVersion) + "): use a newer crankcheck"
                   : "must be " + std::to_string(kSceneFormatVersion) + " (got " + got + ")";
    });
  }
  for (const char* key : {"name", "description"})
    if (const toml::node* text = root.get(key); text != nullptr && !text->is_string())
      fail(source, key, "must be a string");
  static const std::set<std::string> kTopLevel = {"format_version", "name", "description"};
  static const std::set<std::string> kTables = {"engine", "crank", "rod", "piston", "flywheel", "gas", "cylinder",
                                                "balance_shaft", "crankshaft"};
  for (const auto& [k, v] : root) {
    const std::string name(k.str());
    if (!kTables.contains(name) && !kTopLevel.contains(name))
      fail(source, name,
           "unknown key (top level: format_version, name, description; tables: engine, crank, rod, piston, flywheel, "
           "gas, crankshaft, [[cylinder]], [[balance_shaft]])");
  }
  const bool has_gas = root.get("gas") != nullptr;

  Mechanism m;
  // The scene's name, its file's stem, heads its sections and fills the tables' scene column: one line of UTF-8 that
  // prints as itself, whatever the file is called (a newline, an escape sequence, a bidirectional control or bytes
  // that are not UTF-8 shown escaped: "two\nlines.toml" is the scene "two\\nlines"). The path itself opens the file.
  m.name = escapeControls(std::filesystem::path(source).stem().string());

  // [[cylinder]]: one table per cylinder (a layout); without it, one bank of engine.cylinders.
  const toml::array* layout = nullptr;
  if (const toml::node* node = root.get("cylinder")) {
    layout = node->as_array();
    if (layout == nullptr || !layout->is_array_of_tables())
      fail(source, "[[cylinder]]", "must be an array of tables, one [[cylinder]] per cylinder");
    if (layout->empty() || static_cast<long long>(layout->size()) > kMaxCylinders)
      fail(source, "[[cylinder]]", "must have between 1 and 64 tables (got " + std::to_string(layout->size()) + ")");
  }

  TableReader engine(root, "engine", source, true,
                     {"cylinders", "cycle", "acting", "crank_angles_deg", "cylinder_angle_deg", "cylinder_spacing",
                      "speed_rpm", "gravity", "pin_offset"});
  const auto cylinder_count = [](bool, const std::string& got) {
    return "must be between 1 and " + std::to_string(kMaxCylinders) + " (got " + got + ")";
  };
  long long cylinders = 0;
  if (layout != nullptr) {
    cylinders = static_cast<long long>(layout->size());
    if (engine.find("cylinders") != nullptr && engine.integer("cylinders", 1, kMaxCylinders, cylinder_count) != cylinders)
      fail(source, engine.key("cylinders"),
           "must equal the number of [[cylinder]] tables (" + std::to_string(cylinders) + "), or be left out");
    for (const char* key : {"cylinder_angle_deg", "crank_angles_deg", "cylinder_spacing", "pin_offset"})
      if (engine.find(key) != nullptr)
        fail(source, engine.key(key), std::string("must be absent when [[cylinder]] tables place each cylinder") +
                                          (std::string(key) == "pin_offset" ? " (give pin_offset in each [[cylinder]])" : ""));
  } else {
    cylinders = engine.integer("cylinders", 1, kMaxCylinders, cylinder_count);
  }
  m.machine.cylinders = static_cast<int>(cylinders);
  const std::string cycle = engine.string("cycle");
  if (cycle == "two-stroke") m.machine.cycle = Cycle::kTwoStroke;
  else if (cycle == "four-stroke") m.machine.cycle = Cycle::kFourStroke;
  else fail(source, engine.key("cycle"), "must be \"two-stroke\" or \"four-stroke\" (got " + quoteText(cycle) + ")");
  const std::string acting = engine.string("acting", "single");
  if (acting == "single") m.machine.acting = Acting::kSingle;
  else if (acting == "double") m.machine.acting = Acting::kDouble;
  else fail(source, engine.key("acting"), "must be \"single\" or \"double\" (got " + quoteText(acting) + ")");

  if (layout != nullptr) {
    // theta_j = phi + beta_j - gamma_j: alpha_j is the throw angle minus the bank angle (CONVENTIONS, "Layouts").
    size_t with_axial = 0;
    for (size_t j = 0; j < layout->size(); ++j) {
      TableReader cylinder(*layout->get(j)->as_table(), "cylinder[" + std::to_string(j) + "]", source,
                           {"bank_angle_deg", "throw_angle_deg", "axial_position", "firing_angle_deg", "pin_offset"});
      const double bank_deg = cylinder.number("bank_angle_deg");
      const double throw_deg = cylinder.number("throw_angle_deg");
      requireAngleDegrees(bank_deg, source, cylinder.key("bank_angle_deg"));
      requireAngleDegrees(throw_deg, source, cylinder.key("throw_angle_deg"));
      // alpha_j = beta_j - gamma_j obeys the same limit (validateMechanism); said here in the keys the scene has.
      if (std::fabs(throw_deg - bank_deg) > kMaxAngleDeg.value)
        fail(source, cylinder.key("throw_angle_deg"),
             std::string("throw_angle_deg - bank_angle_deg must be at most ") + kMaxAngleDeg.text +
                 " in magnitude (got " + formatNumber(throw_deg - bank_deg) + ")");
      m.machine.bank_angles.push_back(radiansFromDegrees(bank_deg));
      m.machine.crank_angles.push_back(radiansFromDegrees(throw_deg - bank_deg));
      if (const auto z = cylinder.optionalNumber("axial_position")) {
        m.machine.axial_positions.push_back(*z);
        ++with_axial;
      } else {
        m.machine.axial_positions.push_back(0.0);
      }
      if (with_axial != 0 && with_axial != j + 1)
        fail(source, cylinder.key("axial_position"), "give it for every cylinder or for none");
      m.machine.pin_offsets.push_back(cylinder.number("pin_offset", 0.0));  // a cylinder without one is centric
      if (has_gas) {
        const double firing_deg = cylinder.number("firing_angle_deg");
        requireAngleDegrees(firing_deg, source, cylinder.key("firing_angle_deg"));
        m.firing_angles.push_back(radiansFromDegrees(firing_deg));
      } else if (cylinder.find("firing_angle_deg") != nullptr) {
        fail(source, cylinder.key("firing_angle_deg"), "belongs with a [gas] table (the scene has none)");
      }
    }
    if (with_axial == 0) m.machine.axial_positions.clear();
    if (!hasPinOffsets(m)) m.machine.pin_offsets.clear();
    m.machine.explicit_crank_angles = true;
    m.machine.cylinder_angle = m.machine.bank_angles.front();
  } else {
    if (auto angles = engine.optionalNumberArray("crank_angles_deg")) {
      if (static_cast<long long>(angles->size()) != cylinders)
        fail(source, engine.key("crank_angles_deg"),
             "must have one angle per cylinder: " + std::to_string(cylinders) + " expected, got " +
                 std::to_string(angles->size()));
      for (size_t i = 0; i < angles->size(); ++i) {
        requireAngleDegrees((*angles)[i], source, engine.key("crank_angles_deg") + "[" + std::to_string(i) + "]");
        m.machine.crank_angles.push_back(radiansFromDegrees((*angles)[i]));
      }
      m.machine.explicit_crank_angles = true;
    } else {
      m.machine.crank_angles = calcPhaseAngles(m.machine.cylinders, m.machine.cycle, m.machine.acting);
    }
    const double cylinder_angle_deg = engine.number("cylinder_angle_deg");
    requireAngleDegrees(cylinder_angle_deg, source, engine.key("cylinder_angle_deg"));
    m.machine.cylinder_angle = radiansFromDegrees(cylinder_angle_deg);
    if (const auto spacing = engine.optionalNumber("cylinder_spacing")) {
      if (!(std::fabs(*spacing) * static_cast<double>(cylinders - 1) <= kMaxLength.value))
        fail(source, engine.key("cylinder_spacing"),
             std::string("must keep every cylinder within ") + kMaxLength.text + " of the first (got " +
                 formatNumber(*spacing) + ")");
      for (long long j = 0; j < cylinders; ++j) m.machine.axial_positions.push_back(static_cast<double>(j) * *spacing);
    }
    if (const auto delta = engine.optionalNumber("pin_offset"))  // every cylinder of the bank
      m.machine.pin_offsets.assign(static_cast<size_t>(cylinders), *delta);
  }
  m.speed_rpm = engine.number("speed_rpm");
  m.machine.speed = m.speed_rpm * (M_PI / 30.0);
  m.machine.gravity = engine.number("gravity", 9.80665);

  TableReader crank(root, "crank", source, true,
                    {"radius", "mass", "com_radius", "counterweight_mass", "counterweight_radius"});
  m.crank.radius = crank.number("radius");
  m.crank.mass = crank.number("mass");
  m.crank.com_radius = crank.number("com_radius");
  m.crank.counterweight_mass = crank.number("counterweight_mass", 0.0);
  if (m.crank.counterweight_mass > 0) m.crank.counterweight_radius = crank.number("counterweight_radius");
  else m.crank.counterweight_radius = crank.number("counterweight_radius", 0.0);

  TableReader rod(root, "rod", source, true,
                  {"length", "mass", "com_from_wrist_pin", "inertia_about_wrist_pin"});
  m.rod.length = rod.number("length");
  m.rod.mass = rod.number("mass");
  m.rod.com_from_wrist_pin = rod.number("com_from_wrist_pin");
  m.rod.inertia_about_wrist_pin = rod.number("inertia_about_wrist_pin");

  TableReader piston(root, "piston", source, true, {"mass"});
  m.piston.mass = piston.number("mass");

  TableReader flywheel(root, "flywheel", source, false, {"inertia"});
  if (flywheel.present()) m.flywheel_inertia = flywheel.number("inertia");

  // [crankshaft]: the elastic crank train (docs/SCENE-FORMAT.md, "Crankshaft (torsion)"); its rules: validateMechanism.
  TableReader crankshaft(root, "crankshaft", source, false,
                         {"throw_inertia", "front_inertia", "stiffness", "section_damping", "throw_damping"});
  if (crankshaft.present()) {
    CrankshaftParams c;
    c.throw_inertia = crankshaft.number("throw_inertia", 0.0);
    c.front_inertia = crankshaft.number("front_inertia", 0.0);
    const auto stiffness = crankshaft.optionalNumberArray("stiffness");
    if (!stiffness) fail(source, crankshaft.key("stiffness"), "missing key (K_s [N m/rad] per section, front to flywheel)");
    c.stiffness = *stiffness;
    const toml::node* damping = crankshaft.find("section_damping");
    if (damping != nullptr && damping->is_array()) c.section_damping = *crankshaft.optionalNumberArray("section_damping");
    else c.section_damping = {crankshaft.number("section_damping", 0.0)};
    c.throw_damping = crankshaft.number("throw_damping", 0.0);
    m.crankshaft = c;
  }

  if (const toml::node* node = root.get("balance_shaft")) {
    const toml::array* shafts = node->as_array();
    if (shafts == nullptr || !shafts->is_array_of_tables())
      fail(source, "[[balance_shaft]]", "must be an array of tables, one [[balance_shaft]] per shaft");
    if (static_cast<long long>(shafts->size()) > kMaxCylinders)  // as the cylinders: the work per shaft stays bounded
      fail(source, "[[balance_shaft]]", "must have at most 64 tables (got " + std::to_string(shafts->size()) + ")");
    for (size_t i = 0; i < shafts->size(); ++i) {
      TableReader shaft(*shafts->get(i)->as_table(), "balance_shaft[" + std::to_string(i) + "]", source,
                        {"ratio", "mass", "radius", "phase_deg", "position"});
      BalanceShaftParams b;
      b.ratio = shaft.number("ratio");
      b.mass = shaft.number("mass");
      b.radius = shaft.number("radius");
      const double phase_deg = shaft.number("phase_deg", 0.0);
      requireAngleDegrees(phase_deg, source, shaft.key("phase_deg"));
      b.phase = radiansFromDegrees(phase_deg);
      const auto position = shaft.optionalNumberArray("position");
      if (!position) fail(source, shaft.key("position"), "missing key (the shaft's axis, [x, y, z] in m)");
      if (position->size() != 3)
        fail(source, shaft.key("position"), "must be [x, y, z] (got " + std::to_string(position->size()) + " numbers)");
      b.position = {(*position)[0], (*position)[1], (*position)[2]};
      m.balance_shafts.push_back(b);
    }
  }

  TableReader gas(root, "gas", source, false, {"bore", "cycle_angle_deg", "pressure_pa", "firing_order"});
  if (gas.present()) {
    GasParams g;
    g.cycle = m.machine.cycle == Cycle::kFourStroke ? 4.0 * M_PI : 2.0 * M_PI;
    g.bore = gas.number("bore");
    const auto angles = gas.optionalNumberArray("cycle_angle_deg");
    const auto pressures = gas.optionalNumberArray("pressure_pa");
    if (!angles) fail(source, gas.key("cycle_angle_deg"), "missing key");
    if (!pressures) fail(source, gas.key("pressure_pa"), "missing key");
    if (angles->size() != pressures->size())
      fail(source, gas.key("pressure_pa"), "must have one pressure per cycle angle: " + std::to_string(angles->size()) +
                                               " expected, got " + std::to_string(pressures->size()));
    const double cycle_deg = m.machine.cycle == Cycle::kFourStroke ? 720.0 : 360.0;
    for (size_t i = 0; i < angles->size(); ++i) {
      const std::string key = gas.key("cycle_angle_deg") + "[" + std::to_string(i) + "]";
      const double a = (*angles)[i];
      if (i == 0 && a != 0.0) fail(source, key, "must be 0: the table starts at the firing outer dead centre (got " + formatNumber(a) + ")");
      if (i > 0 && !(a > (*angles)[i - 1]))
        fail(source, key, "must be strictly increasing (got " + formatNumber(a) + " after " + formatNumber((*angles)[i - 1]) + ")");
      if (!(a < cycle_deg))
        fail(source, key, "must be below the cycle's " + formatNumber(cycle_deg) + " degrees (got " + formatNumber(a) + ")");
      g.cycle_angles.push_back(radiansFromDegrees(a));
    }
    g.pressures = *pressures;
    // Pressures typed in bar are 1e5 times too small and would pass every bound: a table whose largest |p| is below
    // kMinPeakPressure [Pa] (0.1 bar), which no engine's or compressor's cylinder works at, is refused as one.
    constexpr double kMinPeakPressure = 1e4;
    double peak = 0.0;
    bool finite = true;
    for (double p : g.pressures) {
      finite = finite && std::isfinite(p);
      peak = std::max(peak, std::fabs(p));
    }
    if (finite && !g.pressures.empty() && peak < kMinPeakPressure)
      fail(source, gas.key("pressure_pa"),
           "its largest |pressure| is " + formatNumber(peak) + " Pa, below 1e4 Pa (0.1 bar), which no engine or "
           "compressor cylinder works at: the table is in pascal (one typed in bar is 1e5 times too small: " +
           formatNumber(peak) + " bar is " + formatNumber(peak * 1e5) + " Pa)");
    m.gas = g;
    if (layout == nullptr) {
      // An inline engine: firing_order lists the cylinders in firing order, evenly spaced over the cycle.
      const toml::node* order = gas.find("firing_order");
      if (order == nullptr) fail(source, gas.key("firing_order"), "missing key (an inline scene gives the firing order)");
      const toml::array* list = order->as_array();
      if (list == nullptr || list->size() != static_cast<size_t>(cylinders))
        fail(source, gas.key("firing_order"), "must list each of the " + std::to_string(cylinders) + " cylinders once");
      m.firing_angles.assign(static_cast<size_t>(cylinders), -1.0);
      const std::string index_rule = "must be a cylinder index 0.." + std::to_string(cylinders - 1) + ", each once";
      for (size_t i = 0; i < list->size(); ++i) {
        const std::string key = gas.key("firing_order") + "[" + std::to_string(i) + "]";
        const long long j = integerValue(*list->get(i), source, key, 0, static_cast<int>(cylinders - 1),
                                         [&](bool, const std::string& got) { return index_rule + " (got " + got + ")"; });
        if (m.firing_angles[static_cast<size_t>(j)] >= 0.0) fail(source, key, index_rule + " (got " + std::to_string(j) + " again)");
        m.firing_angles[static_cast<size_t>(j)] = radiansFromDegrees(cycle_deg * static_cast<double>(i) / static_cast<double>(cylinders));
      }
    } else if (gas.find("firing_order") != nullptr) {
      fail(source, gas.key("firing_order"), "must be absent when [[cylinder]] tables give each firing_angle_deg");
    }
  }

  try {
    validateMechanism(m, source);
  } catch (const SceneError& e) {
    throw SceneError(moved_integers.quoteAsTyped(e.what()));
  }
  // The flywheel end of the elastic crank train turns at omega t ("Torsion"): a scene with [crankshaft] needs a speed.
  if (m.crankshaft && !(m.machine.speed > 0.0))
    fail(source, "[engine].speed_rpm",
         "must be > 0 with a [crankshaft] table (its flywheel end turns at the scene's speed) (got " +
             formatNumber(m.speed_rpm) + ")");
  return m;
}

Mechanism loadSceneFile(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(source, "file", "cannot be read (no such regular file)");
  // No scene needs more than a few hundred kilobytes (64 cylinders, a gas table of thousands of points): a larger file
  // is refused before it is read, not read whole (a 2 GB file did not finish in 30 s).
  constexpr std::uintmax_t kMaxSceneBytes = 16u << 20;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxSceneBytes)
    fail(source, "file", "is " + std::to_string(bytes) + " bytes, more than 16 MiB: no scene needs as much");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(source, "file", "cannot be opened");
  std::string content;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {  // at most one buffer past the limit: a file still growing
    content.append(buffer, static_cast<size_t>(in.gcount()));
    if (content.size() > kMaxSceneBytes) fail(source, "file", "is more than 16 MiB: no scene needs as much");
  }
  if (content.find('\0') != std::string::npos) fail(source, "file", "is binary, not a TOML text file");
  return parseScene(content, source);
}

}  // namespace crankcheck
