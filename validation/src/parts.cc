#include "crankcheck/validation/parts.h"

namespace crankcheck::validation {

// The registry: one line per part, in report order. Each names the accessor `const Part& NAME()` that the part's own
// file, validation/src/parts/KEY.cc, defines in namespace parts (README, "Adding a report part").
#define CRANKCHECK_REPORT_PARTS(PART) \
  PART(errorVsLambda)        /*  1 */ \
  PART(speedVsError)         /*  2 */ \
  PART(harmonics)            /*  3 */ \
  PART(gravitySignificance)  /*  4 */ \
  PART(nortonFigure)         /*  5 */ \
  PART(deltaVsK)             /*  6 */ \
  PART(integratorPareto)     /*  7 */ \
  PART(errata)               /*  8 */ \
  PART(balance)              /*  9 */ \
  PART(torqueSplit)          /* 10 */ \
  PART(rodModels)            /* 11 */ \
  PART(pinLoadPolar)         /* 12 */ \
  PART(engines)              /* 13 */ \
  PART(offset)               /* 14 */ \
  PART(flywheel)             /* 15 */ \
  PART(balanceShafts)        /* 16 */

namespace parts {
#define CRANKCHECK_DECLARE_PART(name) const Part& name();
CRANKCHECK_REPORT_PARTS(CRANKCHECK_DECLARE_PART)
#undef CRANKCHECK_DECLARE_PART
}  // namespace parts

const std::vector<const Part*>& listParts() {
#define CRANKCHECK_LIST_PART(name) &parts::name(),
  static const std::vector<const Part*> all = {CRANKCHECK_REPORT_PARTS(CRANKCHECK_LIST_PART)};
#undef CRANKCHECK_LIST_PART
  return all;
}

}  // namespace crankcheck::validation
