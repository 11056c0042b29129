#include "crankcheck/validation/parts.h"

namespace crankcheck::validation {

// Each part's file, validation/src/parts/KEY.cc, defines its accessor.
namespace parts {
const Part& engines();
const Part& offset();
const Part& flywheel();
const Part& balanceShafts();
}  // namespace parts

const std::vector<const Part*>& listParts() {
  // One line per part, in report order.
  static const std::vector<const Part*> all = {
      &parts::engines(),        // 13
      &parts::offset(),         // 14
      &parts::flywheel(),       // 15
      &parts::balanceShafts(),  // 16
  };
  return all;
}

}  // namespace crankcheck::validation
