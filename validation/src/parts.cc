#include "crankcheck/validation/parts.h"

#include <algorithm>
#include <stdexcept>

namespace crankcheck::validation {

// The registry: one line per part, in report order. Each names the accessor `const Part& NAME()` that the part's own
// file, validation/src/parts/KEY.cc, defines in namespace parts (docs/contributing.md, "Adding a report part").
#define CRANKCHECK_REPORT_PARTS(PART) \
  PART(verdict)                       \
  PART(yourEngine)                    \
  PART(summary)                       \
  PART(scenes)                        \
  PART(survey)                        \
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
  PART(torsion)              /* 17 */ \
  PART(steppedEngines)       /* 18 */

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
bool part_registry_built = false;

}  // namespace

void registerExtraPart(const Part& part) {
  if (part_registry_built) throw std::logic_error("registerExtraPart: the part registry is already in use");
  extraParts().push_back(&part);
}

const std::vector<const Part*>& listParts() {
#define CRANKCHECK_LIST_PART(name) &parts::name(),
  static const std::vector<const Part*> all = [] {
    part_registry_built = true;
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
  int n = 0;
  for (const Part* part : listParts()) {
    if (!part->always()) ++n;
    if (part == this) return always() ? 0 : n;
  }
  throw std::logic_error("report part " + key() + " is not registered");
}

const Part& findPart(const std::string& key) {
  for (const Part* part : listParts())
    if (part->key() == key) return *part;
  throw std::logic_error("no report part " + key);
}

std::vector<std::string> listPartKeys() {
  std::vector<std::string> keys;
  for (const Part* part : listParts())
    if (!part->always()) keys.push_back(part->key());
  return keys;
}

void checkPartKeys(const std::vector<std::string>& keys) {
  std::string known;
  const std::vector<std::string> all = listPartKeys();
  for (const std::string& key : all) known += (known.empty() ? "" : ", ") + key;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (std::find(all.begin(), all.end(), keys[i]) == all.end())
      throw std::invalid_argument("no report part \"" + keys[i] + "\"; the parts are " + known);
    if (std::find(keys.begin(), keys.begin() + static_cast<long>(i), keys[i]) != keys.begin() + static_cast<long>(i))
      throw std::invalid_argument("part \"" + keys[i] + "\" is named twice");
  }
}

}  // namespace crankcheck::validation
