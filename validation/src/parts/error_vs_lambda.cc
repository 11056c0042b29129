// Report part `error_vs_lambda` (1): the error of every approximate method against lambda (computed in campaign.cc).
#include <string>
#include <vector>

#include "../campaign_tables.h"
#include "cmath"
#include "crankcheck/validation/part.h"
#include "cstdio"

namespace crankcheck::validation {
namespace {

// The figure's caption.
constexpr const char* kCaption =
    "Max error over the crank turn against lambda, relative to the quantity's scale (r, r w, r w^2 for x, v, a; "
    "the energy scale for Q and U): Norton's two-term x, v, a; Q from Fourier series of order 2-12 with exact "
    "coefficients, from the paper's printed coefficients (eq 15) and with eq (5) as printed; analytic against Simbody";

class ErrorVsLambdaPart final : public Part {
 public:
  std::string key() const override { return "error_vs_lambda"; }
  int number() const override { return 1; }
  std::string title() const override { return "Error against lambda"; }
  // 21 lambdas from 0.01 to 0.95, log spaced; the quick campaign takes every fourth, so that each of its rows is also
  // a row of the full campaign (tests/cli/quick_report_test.cc compares them).
  std::vector<Task> tasks(const PartContext& context) const override {
    std::vector<Task> out;
    for (int i = 0; i <= 20; i += context.quick ? 4 : 1) {
      const double lambda = 0.01 * std::pow(95.0, i / 20.0);
      char id[64];
      std::snprintf(id, sizeof id, "error_vs_lambda lambda=%.3g", lambda);
      out.push_back({id, false, [base = context.base, lambda] { return calcErrorVsLambdaTables(base, lambda); }});
    }
    return out;
  }
  ReportPart describe(const TableSet& tables) const override {
    ReportPart part;
    if (!tables.count("error_vs_lambda")) return part;
    part.heading = heading();
    part.caption = kCaption;
    return part;
  }
  std::vector<std::string> tables() const override { return {"error_vs_lambda"}; }
};

}  // namespace

namespace parts {
const Part& errorVsLambda() {
  static const ErrorVsLambdaPart part;
  return part;
}
}  // namespace parts

}  // namespace crankcheck::validation
