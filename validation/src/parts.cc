#include "crankcheck/validation/parts.h"

#include <algorithm>
#include <stdexcept>

namespace crankcheck::validation {

// The registry: one line per part, in report order. Each names the accessor `const Part& NAME()` that the part's own
// file, validation/src/parts/KEY.cc, defines in namespace parts (docs/contributing.md, "Adding a report part").
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
  PART(balanceShafts)        /* 16 */ \
  PART(torsion)              /* 17 */

namespace parts {
#define CRANKCHECK_DECLARE_PART(name) const Part& name();
CRANKCHECK_REPORT_PARTS(CRANKCHECK_DECLARE_PART)
#undef CRANKCHECK_DECLARE_PART
}  // namespace parts

namespace {

// The parts registerExtraPart added, and whether listParts() has been built (after which none may be added).
std::vector<const Part*>& extraParts() {
  static std::vector<const Part*> extra;
  return extra;
}
bool registry_built = false;

}  // namespace

void registerExtraPart(const Part& part) {
  if (registry_built) throw std::logic_error("registerExtraPart: the part registry is already in use");
  extraParts().push_back(&part);
}

const std::vector<const Part*>& listParts() {
#define CRANKCHECK_LIST_PART(name) &parts::name(),
  static const std::vector<const Part*> all = [] {
    registry_built = true;
    std::vector<const Part*> out = {CRANKCHECK_REPORT_PARTS(CRANKCHECK_LIST_PART)};
    for (const Part* extra : extraParts()) {  // a test build's (registerExtraPart), after the others
      for (const Part* known : out)
        if (known->key() == extra->key())
          throw std::logic_error("registerExtraPart: part \"" + extra->key() + "\" twice");
      out.push_back(extra);
    }
    return out;
  }();
#undef CRANKCHECK_LIST_PART
  return all;
}

int Part::number() const {
  const auto& all = listParts();
  const auto it = std::find(all.begin(), all.end(), this);
  if (it == all.end()) throw std::logic_error("report part " + key() + " is not registered");
  return static_cast<int>(it - all.begin()) + 1;
}

void checkPartKeys(const std::vector<std::string>& keys) {
  std::string known;
  for (const Part* part : listParts()) known += (known.empty() ? "" : ", ") + part->key();
  for (size_t i = 0; i < keys.size(); ++i) {
    const auto& all = listParts();
    if (std::none_of(all.begin(), all.end(), [&](const Part* part) { return part->key() == keys[i]; }))
      throw std::invalid_argument("no report part \"" + keys[i] + "\"; the parts are " + known);
    if (std::find(keys.begin(), keys.begin() + static_cast<long>(i), keys[i]) != keys.begin() + static_cast<long>(i))
      throw std::invalid_argument("part \"" + keys[i] + "\" is named twice");
  }
}

}  // namespace crankcheck::validation
