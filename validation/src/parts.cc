#include "crankcheck/validation/parts.h"

namespace crankcheck::validation {

// Each part's file, validation/src/parts/KEY.cc, defines its accessor.
namespace parts {
const Part& errorVsLambda();
const Part& speedVsError();
const Part& harmonics();
const Part& gravitySignificance();
const Part& nortonFigure();
const Part& deltaVsK();
const Part& integratorPareto();
const Part& errata();
const Part& balance();
const Part& torqueSplit();
const Part& rodModels();
const Part& pinLoadPolar();
const Part& engines();
const Part& offset();
const Part& flywheel();
const Part& balanceShafts();
}  // namespace parts

const std::vector<const Part*>& listParts() {
  // One line per part, in report order.
  static const std::vector<const Part*> all = {
      &parts::errorVsLambda(),        // 1
      &parts::speedVsError(),         // 2
      &parts::harmonics(),            // 3
      &parts::gravitySignificance(),  // 4
      &parts::nortonFigure(),         // 5
      &parts::deltaVsK(),             // 6
      &parts::integratorPareto(),     // 7
      &parts::errata(),               // 8
      &parts::balance(),              // 9
      &parts::torqueSplit(),          // 10
      &parts::rodModels(),            // 11
      &parts::pinLoadPolar(),         // 12
      &parts::engines(),              // 13
      &parts::offset(),               // 14
      &parts::flywheel(),             // 15
      &parts::balanceShafts(),        // 16
  };
  return all;
}

}  // namespace crankcheck::validation
