#pragma once
/// @file
/// The folders crankcheck writes (a report, a shard) and the rule that keeps a user's files safe:
///
///   `--out DIR` may be replaced only when DIR does not exist, is an empty folder, or is a folder that crankcheck
///   itself wrote: it holds the marker crankcheck-manifest.json (tool name, version, kind, and each file crankcheck
///   wrote there with its size and CRC-32) and nothing but those files, each as recorded. Anything else at DIR (a
///   folder with a user's file in it, a file edited since, a plain file, a symbolic link, a manifest that names a
///   path outside the folder) is refused before any work starts, and nothing on disk is changed.
///
/// A folder can come from anyone (a copied report, a shard from another machine, a hand edit), so its manifest is
/// never trusted further than this: what it names is only ever a plain file inside the folder, reached without
/// following a link, with the size and checksum recorded; only such a file is ever removed.
///
/// A run writes into a fresh staging folder beside DIR (same file system), then installs it in one step (a
/// rename, or an exchange of the two folders); only then is the old report removed, file by file as its manifest
/// lists them. A failed or interrupted run removes its staging folder and leaves DIR as it was. Every file is
/// created with O_EXCL | O_NOFOLLOW inside the staging folder: no symbolic link is followed, no file overwritten.

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace crankcheck::validation {

/// The marker every folder crankcheck writes carries.
inline constexpr const char* kManifestName = "crankcheck-manifest.json";

/// crankcheck's version, from the project's `project(VERSION)` in CMake.
const char* getCrankcheckVersion();

/// One file a folder's manifest lists, as crankcheck wrote it.
struct ManifestFile {
  std::string path;         ///< relative to the folder, generic form, no empty, ".", ".." or absolute part
  std::uintmax_t size = 0;  ///< [bytes]
  std::string crc32;        ///< CRC-32 of the content (zlib's), 8 lower-case hex digits
};

/// A folder's crankcheck-manifest.json.
struct FolderManifest {
  std::string version;  ///< the crankcheck that wrote it
  std::string kind;     ///< "report" or "shard"
  std::vector<ManifestFile> files;
};

/// Reads FOLDER/crankcheck-manifest.json.
/// @throws std::runtime_error "PATH: why" when it is missing, not JSON, not crankcheck's, lists a file without its
///   size and checksum (an earlier crankcheck's), or names a path that is not a file inside the folder (absolute,
///   with an empty, "." or ".." part, listed twice, or the manifest itself).
FolderManifest readFolderManifest(const std::filesystem::path& folder);

/// The CRC-32 of `content` as a manifest records it (8 lower-case hex digits).
std::string calcManifestChecksum(std::string_view content);

/// Whether FOLDER/file.path is a plain file, reached without following a symbolic link, with the size and the
/// checksum recorded (nothing is read past the size: a grown file is not read to its end).
bool isAsRecorded(const std::filesystem::path& folder, const ManifestFile& file);

/// Checks `--out` against the rule above without touching the disk. Also refused: a target inside a folder crankcheck
/// wrote (a report or shard: it would then hold a file crankcheck did not write and refuse every later run), and a
/// path the file system cannot hold (a name over NAME_MAX with the staging folder's suffix, a path over PATH_MAX).
/// @throws UsageError "FLAG: PATH: rule" when the rule refuses it.
void checkOutputFolder(const std::filesystem::path& target, const std::string& flag);

/// Checks a new file a flag names (`validate --profile FILE`) before any work: it must not exist, its folder must, its
/// names must fit the file system, and it must lie neither inside a folder crankcheck wrote nor inside any of
/// `outputs` (the run's own output folders, which may not exist yet).
/// @throws UsageError "FLAG: PATH: rule".
void checkNewFile(const std::filesystem::path& file, const std::string& flag,
                  const std::vector<std::filesystem::path>& outputs);

/// Creates `path` (which must not exist) and writes `content` into it: O_CREAT | O_EXCL | O_NOFOLLOW, every byte
/// checked, closed with its error checked; a failed write removes the file again.
/// @throws EnvironmentError "PATH: cannot write: reason" (disk full, write refused, ...).
void writeNewFile(const std::filesystem::path& path, std::string_view content);

/// The previous report, moved aside to `old_folder` by an install into `target`, removed as its manifest lists it:
/// only a plain file as recorded, then the manifest and the emptied folders. What remains (a file added or changed
/// since the folder was checked, or everything when its manifest cannot be read) is never removed: the folder is
/// renamed to TARGET.previous (TARGET.previous-2, ... up to -99; no existing path is replaced) beside the target,
/// where it can be found, and a warning on stderr names that path and up to three of the files kept. It stays at
/// `old_folder` (a hidden name) only when no such name is free, and the warning then says so.
/// @return where the remains are (empty when everything was removed).
std::filesystem::path removePreviousReport(const std::filesystem::path& old_folder, const std::filesystem::path& target);

/// An output folder being written: checked on construction, staged, installed or abandoned.
class OutputFolder {
 public:
  /// Checks the rule (checkOutputFolder); creates nothing yet.
  /// @throws UsageError as checkOutputFolder.
  OutputFolder(std::filesystem::path target, std::string flag);
  /// Abandons the staging folder unless it was installed.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Creates the missing parent folders of the target and an empty staging folder beside it.
  /// @throws EnvironmentError when they cannot be created (a write refused, a full disk).
  /// @throws UsageError when a parent of the target is not a folder.
  void createStaging();
  /// The staging folder, where the caller writes (empty before createStaging).
  const std::filesystem::path& getStaging() const { return staging_; }
  const std::filesystem::path& getTarget() const { return target_; }

  /// Writes the manifest (`kind`: "report" or "shard"; it lists every file under the staging folder), checks the
  /// rule on the target once more, and puts the staging folder in the target's place; then removes the previous
  /// report crankcheck wrote there. @throws UsageError if the target changed meanwhile so that the rule refuses it;
  /// EnvironmentError if the swap fails (the target is then as it was).
  void install(const std::string& kind);

  /// Removes the staging folder (and the parents createStaging made) if not installed; finishes removing the
  /// previous report if installed. Safe to call from another thread (an interrupt) at any time, and more than once.
  void abandon();

 private:
  std::mutex mutex_;
  std::filesystem::path target_;
  std::string flag_;
  std::filesystem::path staging_;
  std::vector<std::filesystem::path> created_parents_;  // made by createStaging, deepest last
  std::filesystem::path old_;                           // the previous report after the swap, until removed
  bool installed_ = false;
};

}  // namespace crankcheck::validation
