#include "crankcheck/validation/install_paths.h"

#include <cstdlib>
#include <system_error>

#include "crankcheck/validation/errors.h"

#if !defined(CRANKCHECK_REPORTS_RELATIVE_DIR) || !defined(CRANKCHECK_REPORTS_INSTALLED_DIR)
#error "CRANKCHECK_REPORTS_RELATIVE_DIR and CRANKCHECK_REPORTS_INSTALLED_DIR must be defined by the build"
#endif

namespace crankcheck::validation {
namespace fs = std::filesystem;

fs::path findReportsDir() {
  if (const char* env = std::getenv("CRANKCHECK_REPORTS_DIR")) return env;
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  fs::path beside_program;
  if (!ec) {
    beside_program = program.parent_path().parent_path() / CRANKCHECK_REPORTS_RELATIVE_DIR;
    if (fs::is_directory(beside_program, ec)) return beside_program;
  }
  const fs::path installed = CRANKCHECK_REPORTS_INSTALLED_DIR;
  if (fs::is_directory(installed, ec)) return installed;
  throw EnvironmentError("the gnuplot scripts of the report were not found in " +
                         (beside_program.empty() ? std::string() : quotePath(beside_program) + " or ") +
                         quotePath(installed) + " (set CRANKCHECK_REPORTS_DIR to their folder)");
}

}  // namespace crankcheck::validation
