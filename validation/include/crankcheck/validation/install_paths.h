#pragma once
/// @file
/// Where crankcheck finds the files it ships beside its program: the gnuplot scripts of the report's figures and
/// the example scenes (report part pin_load_polar).
///
/// The build tree and the install tree have the same layout, PREFIX/bin/crankcheck beside
/// PREFIX/share/crankcheck/{reports,scenes} (the build tree links them to the sources' reports/ and scenes/), so the
/// program finds them relative to itself, wherever the tree was installed or moved.

#include <filesystem>

namespace crankcheck::validation {

/// The folder of the gnuplot scripts, the first of:
///  1. the environment variable CRANKCHECK_REPORTS_DIR, when set (never passed over for another folder: set to an
///     empty value or to what is not a folder, it is refused, so that a wrong setting is reported instead of
///     silently replaced);
///  2. ../share/crankcheck/reports relative to the running program's folder (/proc/self/exe), when it exists;
///  3. the folder `cmake --install` put them in for the configured prefix, when it exists (a program of the user's
///     that links crankcheck::validation from an install tree).
/// @throws EnvironmentError naming the places looked at when none exists; UsageError "VARIABLE: ..." for a variable
///         set empty or to what is not a folder.
std::filesystem::path findReportsDir();

/// The folder of the example scenes: as findReportsDir, with CRANKCHECK_SCENES_DIR and share/crankcheck/scenes.
/// @throws as findReportsDir.
std::filesystem::path findScenesDir();

}  // namespace crankcheck::validation
