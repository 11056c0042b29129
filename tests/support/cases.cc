#include "cases.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace crankcheck::testing {

const std::vector<double>& sweepLambdas() {
  static const std::vector<double> v{1e-6, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.9, 0.999};
  return v;
}
const std::vector<double>& sweepModerateLambdas() {
  static const std::vector<double> v{1e-6, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.9};
  return v;
}
const std::vector<double>& sweepGammasDeg() {
  static const std::vector<double> v{0.0, 180.0, 90.0, -90.0, 37.0};
  return v;
}
const std::vector<double>& sweepPhisDeg() {
  static const std::vector<double> v{0.0, 17.0, 45.0, 90.0, 133.0, 180.0, 222.5, 270.0, 300.0, 359.0, -60.0};
  return v;
}

Mechanism makeMechanism(const CaseSpec& spec) {
  Mechanism m;
  m.name = caseName(spec);
  m.machine.cylinders = spec.cylinders;
  m.machine.cycle = spec.cycle;
  m.machine.acting = spec.acting;
  m.machine.crank_angles = calcPhaseAngles(spec.cylinders, spec.cycle, spec.acting);
  m.machine.cylinder_angle = radiansFromDegrees(spec.gamma_deg);
  m.speed_rpm = spec.rpm;
  m.machine.speed = spec.rpm * (M_PI / 30.0);
  m.machine.gravity = 9.80665;
  m.crank.radius = 0.05;
  m.crank.mass = 1.7;
  m.crank.com_radius = 0.4 * m.crank.radius;
  m.crank.counterweight_mass = 1.3;
  m.crank.counterweight_radius = 0.8 * m.crank.radius;
  m.rod.length = m.crank.radius / spec.lambda;
  m.rod.mass = 0.61;
  m.rod.com_from_wrist_pin = 0.3 * m.rod.length;
  const double radius_of_gyration = 0.27 * m.rod.length;
  m.rod.inertia_about_wrist_pin = m.rod.mass * (m.rod.com_from_wrist_pin * m.rod.com_from_wrist_pin +
                                                radius_of_gyration * radius_of_gyration);
  m.piston.mass = 0.43;
  m.flywheel_inertia = 0.2;
  return m;
}

Mechanism makeMechanism(CaseSpec spec, double lambda) {
  spec.lambda = lambda;
  return makeMechanism(spec);
}

namespace {
std::string numberTag(double x, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, std::fabs(x));
  std::string s(buffer);
  std::replace(s.begin(), s.end(), '.', 'p');
  return (x < 0 ? "m" : "") + s;
}
}  // namespace

std::string lambdaTag(double lambda) {
  if (lambda < 1e-3) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.0e", lambda);
    std::string s(buffer);
    std::replace(s.begin(), s.end(), '-', 'm');
    std::replace(s.begin(), s.end(), '+', 'p');
    return s;
  }
  return numberTag(lambda, lambda >= 0.9 && lambda != 0.9 ? 3 : 2);
}

std::string caseNameWithoutLambda(const CaseSpec& spec) {
  std::string name = "k" + std::to_string(spec.cylinders) + (spec.cycle == Cycle::kTwoStroke ? "_two" : "_four");
  if (spec.acting == Acting::kDouble) name += "_double";
  return name + "_gamma" + numberTag(spec.gamma_deg, 0);
}

std::string caseName(const CaseSpec& spec) {
  std::string name = "k" + std::to_string(spec.cylinders) + (spec.cycle == Cycle::kTwoStroke ? "_two" : "_four");
  if (spec.acting == Acting::kDouble) name += "_double";
  return name + "_lambda" + lambdaTag(spec.lambda) + "_gamma" + numberTag(spec.gamma_deg, 0) + "_" +
         numberTag(spec.rpm, 0) + "rpm";
}

void PrintTo(const CaseSpec& spec, std::ostream* os) { *os << caseName(spec); }

::testing::AssertionResult isClose(double a, double b, double tol) {
  const double diff = std::fabs(a - b);
  if (diff <= tol) return ::testing::AssertionSuccess();
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "  a = %.17g\n  b = %.17g\n  |a - b| = %.3e > tol = %.3e (%.2f x tol)", a, b,
                diff, tol, tol > 0 ? diff / tol : INFINITY);
  return ::testing::AssertionFailure() << buffer;
}

}  // namespace crankcheck::testing
