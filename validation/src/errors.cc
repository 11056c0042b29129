#include "crankcheck/validation/errors.h"

namespace crankcheck {

std::string quotePath(const std::filesystem::path& path) { return quoteText(path.string()); }

}  // namespace crankcheck
