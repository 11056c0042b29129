#include "crankcheck/scene/scene_file.h"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <toml++/toml.h>

namespace crankcheck {
namespace {

// Largest magnitude accepted for any number in a scene: far beyond any machine (1e6 m, 1e6 kg, 1e6 rpm),
// small enough that products of a few values cannot overflow.
constexpr double kMaxMagnitude = 1e6;
constexpr int kMaxCylinders = 64;

std::string formatNumber(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

[[noreturn]] void fail(const std::string& source, const std::string& key, const std::string& rule) {
  throw SceneError(source + ": " + key + ": " + rule);
}

// Reads one table of the scene, keeping track of which keys were used so that unknown keys are refused.
class TableReader {
 public:
  // Refuses unknown keys first, so that a misspelt key is reported as such, not as a missing one.
  TableReader(const toml::table& root, std::string name, std::string source, bool required,
              std::set<std::string> allowed)
      : name_(std::move(name)), source_(std::move(source)), allowed_(std::move(allowed)) {
    const toml::node* node = root.get(name_);
    if (node == nullptr) {
      if (required) fail(source_, "[" + name_ + "]", "missing table");
      return;
    }
    table_ = node->as_table();
    if (table_ == nullptr) fail(source_, "[" + name_ + "]", "must be a table");
    for (const auto& [k, v] : *table_) {
      const std::string key_name(k.str());
      if (!allowed_.contains(key_name)) {
        std::string list;
        for (const std::string& a : allowed_) list += (list.empty() ? "" : ", ") + a;
        fail(source_, key(key_name), "unknown key (allowed: " + list + ")");
      }
    }
  }

  bool present() const { return table_ != nullptr; }
  std::string key(const std::string& k) const { return "[" + name_ + "]." + k; }

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

  long long integer(const std::string& k) {
    const toml::node* node = find(k);
    if (node == nullptr) fail(source_, key(k), "missing key");
    if (!node->is_integer()) fail(source_, key(k), "must be an integer");
    return node->as_integer()->get();
  }

  std::string string(const std::string& k, std::optional<std::string> fallback = std::nullopt) {
    const toml::node* node = find(k);
    if (node == nullptr) {
      if (fallback) return *fallback;
      fail(source_, key(k), "missing key");
    }
    if (!node->is_string()) fail(source_, key(k), "must be a string");
    return node->as_string()->get();
  }

  std::optional<std::vector<double>> optionalNumberArray(const std::string& k) {
    const toml::node* node = find(k);
    if (node == nullptr) return std::nullopt;
    const toml::array* array = node->as_array();
    if (array == nullptr) fail(source_, key(k), "must be an array of numbers");
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
      x = static_cast<double>(node.as_integer()->get());
    } else {
      fail(source_, key_name, "must be a number");
    }
    if (!std::isfinite(x)) fail(source_, key_name, "must be finite (got " + formatNumber(x) + ")");
    if (std::fabs(x) > kMaxMagnitude)
      fail(source_, key_name, "magnitude must be at most 1e6 (got " + formatNumber(x) + ")");
    return x;
  }

  std::string name_;
  std::string source_;
  std::set<std::string> allowed_;
  const toml::table* table_ = nullptr;
};

}  // namespace

void validateMechanism(const Mechanism& m, const std::string& source) {
  auto require = [&](bool ok, const std::string& key, const std::string& rule, double got) {
    if (!ok) fail(source, key, rule + " (got " + formatNumber(got) + ")");
  };
  const auto finite = [](double x) { return std::isfinite(x); };
  require(m.engine.cylinders >= 1 && m.engine.cylinders <= kMaxCylinders, "[engine].cylinders",
          "must be between 1 and 64", m.engine.cylinders);
  require(static_cast<int>(m.engine.crank_angles.size()) == m.engine.cylinders, "[engine].crank_angles_deg",
          "must have one angle per cylinder", static_cast<double>(m.engine.crank_angles.size()));
  for (double a : m.engine.crank_angles) require(finite(a), "[engine].crank_angles_deg", "must be finite", a);
  require(finite(m.engine.cylinder_angle), "[engine].cylinder_angle_deg", "must be finite",
          m.engine.cylinder_angle);
  require(finite(m.engine.speed) && m.engine.speed >= 0, "[engine].speed_rpm", "must be >= 0", m.speed_rpm);
  require(finite(m.engine.gravity) && m.engine.gravity >= 0, "[engine].gravity", "must be >= 0",
          m.engine.gravity);
  require(finite(m.crank.radius) && m.crank.radius > 0, "[crank].radius", "must be > 0", m.crank.radius);
  require(finite(m.crank.mass) && m.crank.mass >= 0, "[crank].mass", "must be >= 0", m.crank.mass);
  require(finite(m.crank.com_radius) && m.crank.com_radius >= 0, "[crank].com_radius", "must be >= 0",
          m.crank.com_radius);
  require(finite(m.crank.counterweight_mass) && m.crank.counterweight_mass >= 0, "[crank].counterweight_mass",
          "must be >= 0", m.crank.counterweight_mass);
  require(finite(m.crank.counterweight_radius) && m.crank.counterweight_radius >= 0,
          "[crank].counterweight_radius", "must be >= 0", m.crank.counterweight_radius);
  require(finite(m.rod.length) && m.rod.length > 0, "[rod].length", "must be > 0", m.rod.length);
  require(m.crank.radius < m.rod.length, "[crank].radius",
          "lambda = r / l must be < 1 (rod length " + formatNumber(m.rod.length) + " m)",
          m.crank.radius / m.rod.length);
  require(finite(m.rod.mass) && m.rod.mass >= 0, "[rod].mass", "must be >= 0", m.rod.mass);
  require(finite(m.rod.com_from_wrist_pin) && m.rod.com_from_wrist_pin >= 0 &&
              m.rod.com_from_wrist_pin <= m.rod.length,
          "[rod].com_from_wrist_pin", "must lie on the rod, 0 <= z_k <= l", m.rod.com_from_wrist_pin);
  const double inertia_of_point_mass = m.rod.mass * m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin;
  require(finite(m.rod.inertia_about_wrist_pin) && m.rod.inertia_about_wrist_pin >= inertia_of_point_mass,
          "[rod].inertia_about_wrist_pin",
          "must be >= m_k z_k^2 = " + formatNumber(inertia_of_point_mass) + " kg m^2",
          m.rod.inertia_about_wrist_pin);
  require(finite(m.piston.mass) && m.piston.mass >= 0, "[piston].mass", "must be >= 0", m.piston.mass);
  if (m.flywheel_inertia)
    require(finite(*m.flywheel_inertia) && *m.flywheel_inertia > 0, "[flywheel].inertia", "must be > 0",
            *m.flywheel_inertia);
}

Mechanism parseScene(std::string_view text, const std::string& source) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    fail(source, "line " + std::to_string(where.line) + ", column " + std::to_string(where.column),
         "not valid TOML: " + std::string(e.description()));
  }
  static const std::set<std::string> kTables = {"engine", "crank", "rod", "piston", "flywheel"};
  for (const auto& [k, v] : root) {
    const std::string name(k.str());
    if (!kTables.contains(name)) fail(source, name, "unknown key (tables: engine, crank, rod, piston, flywheel)");
  }

  Mechanism m;
  m.name = std::filesystem::path(source).stem().string();

  TableReader engine(root, "engine", source, true,
                     {"cylinders", "cycle", "acting", "crank_angles_deg", "cylinder_angle_deg", "speed_rpm", "gravity"});
  const long long cylinders = engine.integer("cylinders");
  if (cylinders < 1 || cylinders > kMaxCylinders)
    fail(source, engine.key("cylinders"), "must be between 1 and 64 (got " + std::to_string(cylinders) + ")");
  m.engine.cylinders = static_cast<int>(cylinders);
  const std::string cycle = engine.string("cycle");
  if (cycle == "two-stroke") m.engine.cycle = Cycle::kTwoStroke;
  else if (cycle == "four-stroke") m.engine.cycle = Cycle::kFourStroke;
  else fail(source, engine.key("cycle"), "must be \"two-stroke\" or \"four-stroke\" (got \"" + cycle + "\")");
  const std::string acting = engine.string("acting", "single");
  if (acting == "single") m.engine.acting = Acting::kSingle;
  else if (acting == "double") m.engine.acting = Acting::kDouble;
  else fail(source, engine.key("acting"), "must be \"single\" or \"double\" (got \"" + acting + "\")");
  if (auto angles = engine.optionalNumberArray("crank_angles_deg")) {
    if (static_cast<long long>(angles->size()) != cylinders)
      fail(source, engine.key("crank_angles_deg"),
           "must have one angle per cylinder: " + std::to_string(cylinders) + " expected, got " +
               std::to_string(angles->size()));
    for (double degrees : *angles) m.engine.crank_angles.push_back(radiansFromDegrees(degrees));
    m.engine.explicit_crank_angles = true;
  } else {
    m.engine.crank_angles = calcPhaseAngles(m.engine.cylinders, m.engine.cycle, m.engine.acting);
  }
  m.engine.cylinder_angle = radiansFromDegrees(engine.number("cylinder_angle_deg"));
  m.speed_rpm = engine.number("speed_rpm");
  m.engine.speed = m.speed_rpm * (M_PI / 30.0);
  m.engine.gravity = engine.number("gravity", 9.80665);

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

  validateMechanism(m, source);
  return m;
}

Mechanism loadSceneFile(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(source, "file", "cannot be read (no such regular file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(source, "file", "cannot be opened");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string content = text.str();
  if (content.find('\0') != std::string::npos) fail(source, "file", "is binary, not a TOML text file");
  return parseScene(content, source);
}

}  // namespace crankcheck
