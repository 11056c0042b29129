#include "crankcheck/validation/layouts.h"

#include <cmath>

namespace crankcheck::validation {
namespace {

constexpr double kThrowSpacing = 0.1;   // [m] between throws along the shaft
constexpr double kPairOffset = 0.02;    // [m] between the two cylinders of a shared pin

// One bank at 90 deg, one cylinder per throw.
Layout inlineLayout(const std::string& name, const std::string& description, const std::vector<double>& throws) {
  Layout layout{name, description, {}, {}};
  for (size_t i = 0; i < throws.size(); ++i) layout.cylinders.push_back({90.0, throws[i], kThrowSpacing * i});
  return layout;
}

// Two banks at 90 +- v/2 (left first on each pin), each pin shared by one cylinder of each bank.
Layout vLayout(const std::string& name, const std::string& description, double v_deg, const std::vector<double>& throws) {
  Layout layout{name, description, {}, {}};
  for (size_t i = 0; i < throws.size(); ++i) {
    layout.cylinders.push_back({90.0 + 0.5 * v_deg, throws[i], kThrowSpacing * i});
    layout.cylinders.push_back({90.0 - 0.5 * v_deg, throws[i], kThrowSpacing * i + kPairOffset});
  }
  return layout;
}

// Opposed banks at 0 and 180 deg; each opposed pair on throws 180 deg apart (the pistons meet their outer dead
// centres together), each cylinder on its own throw.
Layout boxerLayout(const std::string& name, const std::string& description, const std::vector<double>& throws) {
  Layout layout{name, description, {}, {}};
  for (size_t i = 0; i < throws.size(); ++i) {
    layout.cylinders.push_back({0.0, throws[i], kThrowSpacing * (2 * i)});
    layout.cylinders.push_back({180.0, throws[i] + 180.0, kThrowSpacing * (2 * i + 1)});
  }
  return layout;
}

}  // namespace

std::vector<Layout> getBalanceLayouts() {
  // Textbook claims {F1, F2, M1, M2}: true = vanishes.
  const TextbookBalance all{true, true, true, true};
  std::vector<Layout> layouts = {
      inlineLayout("inline1", "single cylinder", {0}),
      inlineLayout("inline2", "inline twin, throws 0, 180", {0, 180}),
      inlineLayout("inline3", "inline three, throws 0, 120, 240", {0, 120, 240}),
      inlineLayout("inline4", "inline four, throws 0, 180, 180, 0", {0, 180, 180, 0}),
      inlineLayout("inline5", "inline five, throws 0, 144, 288, 72, 216", {0, 144, 288, 72, 216}),
      inlineLayout("inline6", "inline six, throws 0, 120, 240, 240, 120, 0", {0, 120, 240, 240, 120, 0}),
      inlineLayout("inline8", "inline eight, throws 0, 180, 90, 270, 270, 90, 180, 0", {0, 180, 90, 270, 270, 90, 180, 0}),
      inlineLayout("inline12", "inline twelve, throws 0, 60, ..., 300, 300, ..., 0 (mirror-symmetric)",
                   {0, 60, 120, 180, 240, 300, 300, 240, 180, 120, 60, 0}),
      vLayout("V6_60", "V6, 60 deg, three shared pins at 0, 120, 240", 60.0, {0, 120, 240}),
      vLayout("V6_90", "V6, 90 deg, three shared pins at 0, 120, 240", 90.0, {0, 120, 240}),
      vLayout("V8_cross_plane", "V8, 90 deg, cross-plane crank (pins 0, 90, 270, 180)", 90.0, {0, 90, 270, 180}),
      vLayout("V8_flat_plane", "V8, 90 deg, flat-plane crank (pins 0, 180, 180, 0)", 90.0, {0, 180, 180, 0}),
      vLayout("V12_60", "V12, 60 deg, pins 0, 120, 240, 240, 120, 0", 60.0, {0, 120, 240, 240, 120, 0}),
      boxerLayout("boxer4", "boxer four, opposed pairs on throws 0/180 and 180/0", {0, 180}),
      boxerLayout("boxer6", "boxer six, opposed pairs on throws 0/180, 120/300, 240/60", {0, 120, 240}),
      vLayout("V_twin_45", "V-twin, 45 deg, one shared pin", 45.0, {0}),
  };
  const TextbookBalance claims[] = {
      {false, false, true, true},   // inline1: one plane, no couple
      {true, false, false, true},   // inline2
      {true, true, false, false},   // inline3
      {true, false, true, true},    // inline4
      {true, true, false, false},   // inline5
      all, all, all,                // inline6, inline8, inline12
      {true, true, false, false},   // V6_60
      {true, true, false, false},   // V6_90
      {true, true, false, true},    // V8_cross_plane: a rotating primary couple (for counterweights)
      {true, false, true, true},    // V8_flat_plane: a horizontal secondary force
      all,                          // V12_60
      {true, true, true, false},    // boxer4: a secondary rocking couple
      all,                          // boxer6
      {false, false, {}, {}},       // V_twin_45
  };
  for (size_t i = 0; i < layouts.size(); ++i) layouts[i].textbook = claims[i];
  Layout radial{"radial5", "five-cylinder radial, every rod on one crank pin (no master rod), banks 72 deg apart", {}, {}};
  for (int j = 0; j < 5; ++j) radial.cylinders.push_back({90.0 + 72.0 * j, 0.0, 0.0});
  radial.textbook = {false, true, true, true};  // a rotating primary force of constant size (for a counterweight)
  layouts.push_back(radial);
  // The crank centre O at the middle of the engine (mean z = 0): the shaking moment about O is then the couple
  // the balance tables speak of, not that couple plus z x the free force.
  for (Layout& layout : layouts) {
    double mean = 0.0;
    for (const CylinderPlace& c : layout.cylinders) mean += c.axial_position;
    mean /= static_cast<double>(layout.cylinders.size());
    for (CylinderPlace& c : layout.cylinders) c.axial_position = std::round((c.axial_position - mean) * 1e9) / 1e9;
  }
  return layouts;
}

Mechanism makeLayoutMechanism(const Layout& layout, const Mechanism& parts, double rotation_deg) {
  Mechanism m = parts;
  m.name = layout.name + "_rot" + std::to_string(static_cast<int>(std::lround(rotation_deg)));
  m.machine.cylinders = static_cast<int>(layout.cylinders.size());
  m.machine.cycle = Cycle::kFourStroke;
  m.machine.acting = Acting::kSingle;
  m.machine.explicit_crank_angles = true;
  m.machine.crank_angles.clear();
  m.machine.bank_angles.clear();
  m.machine.axial_positions.clear();
  m.machine.pin_offsets.clear();  // the textbook's layouts are centric
  m.gas.reset();                 // and without gas: a pressure table needs a firing angle per cylinder of the layout
  m.firing_angles.clear();
  m.crankshaft.reset();          // and rigid: a [crankshaft] has one section per throw of the scene it came with
  for (const CylinderPlace& c : layout.cylinders) {
    m.machine.bank_angles.push_back(radiansFromDegrees(c.bank_deg + rotation_deg));
    m.machine.crank_angles.push_back(radiansFromDegrees(c.throw_deg - c.bank_deg));  // theta offset: beta - gamma
    m.machine.axial_positions.push_back(c.axial_position);
  }
  m.machine.cylinder_angle = m.machine.bank_angles.front();
  return m;
}

}  // namespace crankcheck::validation
