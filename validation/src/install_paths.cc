#include "crankcheck/validation/install_paths.h"

#include <cstdlib>
#include <string>
#include <system_error>

#include "crankcheck/validation/errors.h"

#if !defined(CRANKCHECK_DATA_RELATIVE_DIR) || !defined(CRANKCHECK_DATA_INSTALLED_DIR)
#error "CRANKCHECK_DATA_RELATIVE_DIR and CRANKCHECK_DATA_INSTALLED_DIR must be defined by the build"
#endif

namespace crankcheck::validation {
namespace fs = std::filesystem;

namespace {

// share/crankcheck/NAME beside the program, or where the install put it; the environment variable first. A variable
// that is set names the folder: empty or not a folder, it is the user's mistake (an empty one read the current
// folder's scenes as the examples), never passed over for another folder.
fs::path findDataDir(const std::string& name, const char* variable, const std::string& what) {
  std::error_code ec;
  if (const char* env = std::getenv(variable)) {
    if (*env == '\0') throw UsageError(std::string(variable) + ": set but empty; unset it, or set it to the folder of " + what);
    if (!fs::is_directory(env, ec))
      throw UsageError(std::string(variable) + ": " + quotePath(env) + ": not a folder (it should hold " + what + ")");
    return env;
  }
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  fs::path beside_program;
  if (!ec) {
    beside_program = program.parent_path().parent_path() / CRANKCHECK_DATA_RELATIVE_DIR / name;
    if (fs::is_directory(beside_program, ec)) return beside_program;
  }
  const fs::path installed = fs::path(CRANKCHECK_DATA_INSTALLED_DIR) / name;
  if (fs::is_directory(installed, ec)) return installed;
  throw EnvironmentError(what + " were not found in " +
                         (beside_program.empty() ? std::string() : quotePath(beside_program) + " or ") +
                         quotePath(installed) + " (set " + variable + " to their folder)");
}

}  // namespace

fs::path findReportsDir() { return findDataDir("reports", "CRANKCHECK_REPORTS_DIR", "the gnuplot scripts of the report"); }

fs::path findScenesDir() { return findDataDir("scenes", "CRANKCHECK_SCENES_DIR", "the example scenes"); }

}  // namespace crankcheck::validation
