#include "crankcheck/validation/output_folder.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <string>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <boost/crc.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "crankcheck/validation/errors.h"

#ifndef CRANKCHECK_VERSION
#error "CRANKCHECK_VERSION (the project's version) must be defined by the build"
#endif

namespace crankcheck::validation {
namespace fs = std::filesystem;

const char* getCrankcheckVersion() { return CRANKCHECK_VERSION; }

std::string calcManifestChecksum(std::string_view content) {
  boost::crc_32_type crc;
  crc.process_bytes(content.data(), content.size());
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(crc.checksum()));
  return hex;
}

namespace {

constexpr const char* kRule =
    "crankcheck writes only into a folder that does not exist, is empty, or holds a report it wrote itself "
    "(marked by crankcheck-manifest.json)";

// The target as an absolute, normal path without a trailing separator ("." and "dir/" name the folder itself).
fs::path normalTarget(const fs::path& target) {
  fs::path p = fs::absolute(target).lexically_normal();
  if (p.filename().empty() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  return p;
}

[[noreturn]] void refuse(const std::string& flag, const fs::path& target, const std::string& why) {
  throw UsageError(flag + ": " + quotePath(target) + ": " + why);
}

// Why `rel` (a manifest's path) is not the name of a file inside the folder; empty if it is.
std::string whyNotInside(const std::string& rel) {
  if (rel.empty()) return "an empty path";
  if (rel.front() == '/') return "an absolute path";
  if (rel.find('\0') != std::string::npos) return "a path with a NUL byte";
  if (rel == kManifestName) return "the manifest itself";
  for (size_t begin = 0;;) {
    const size_t slash = rel.find('/', begin);
    const std::string part = rel.substr(begin, slash == std::string::npos ? std::string::npos : slash - begin);
    if (part.empty()) return "a path with an empty part";
    if (part == "." || part == "..") return "a path through \"" + part + "\"";
    if (slash == std::string::npos) return {};
    begin = slash + 1;
  }
}

// Opens FOLDER/rel for reading without following a symbolic link on the way (every part a real folder, the last a
// plain file, FOLDER itself not a link). Returns the file's descriptor and its folder's (for unlinkat); -1 and -1 if
// any part is not so. O_NONBLOCK: a FIFO put there never blocks the open.
std::pair<int, int> openInside(const fs::path& folder, const std::string& rel) {
  int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (dir < 0) return {-1, -1};
  size_t begin = 0;
  for (size_t slash; (slash = rel.find('/', begin)) != std::string::npos; begin = slash + 1) {
    const int next = ::openat(dir, rel.substr(begin, slash - begin).c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    ::close(dir);
    if (next < 0) return {-1, -1};
    dir = next;
  }
  const int fd = ::openat(dir, rel.substr(begin).c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    if (fd >= 0) ::close(fd);
    ::close(dir);
    return {-1, -1};
  }
  return {fd, dir};
}

// Whether the open plain file `fd` holds exactly `file.size` bytes with the recorded checksum; no more is read.
bool matchesRecord(int fd, const ManifestFile& file) {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || static_cast<std::uintmax_t>(st.st_size) != file.size) return false;
  boost::crc_32_type crc;
  char buffer[1 << 16];
  std::uintmax_t done = 0;
  while (done < file.size) {
    const ssize_t n = ::read(fd, buffer, static_cast<size_t>(std::min<std::uintmax_t>(sizeof buffer, file.size - done)));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    crc.process_bytes(buffer, static_cast<size_t>(n));
    done += static_cast<std::uintmax_t>(n);
  }
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(crc.checksum()));
  return file.crc32 == hex;
}

// Removes FOLDER/file.path if it is a plain file as recorded (isAsRecorded), unlinked from the folder it was checked
// in; true if removed.
bool removeIfAsRecorded(const fs::path& folder, const ManifestFile& file) {
  const auto [fd, dir] = openInside(folder, file.path);
  if (fd < 0) return false;
  const bool ours = matchesRecord(fd, file);
  ::close(fd);
  const std::string name = fs::path(file.path).filename().string();
  const bool removed = ours && ::unlinkat(dir, name.c_str(), 0) == 0;
  ::close(dir);
  return removed;
}

// Every entry under `folder`, relative, generic form; no symbolic link followed.
std::vector<fs::directory_entry> entriesUnder(const fs::path& folder) {
  std::vector<fs::directory_entry> entries;
  for (auto it = fs::recursive_directory_iterator(folder); it != fs::recursive_directory_iterator(); ++it)
    entries.push_back(*it);
  return entries;
}

bool parentsListed(const std::string& relative_dir, const std::map<std::string, ManifestFile>& files) {
  const std::string prefix = relative_dir + "/";
  return std::any_of(files.begin(), files.end(), [&](const auto& f) { return f.first.rfind(prefix, 0) == 0; });
}

// The staging folder's name beside a target NAME: ".NAME" + this + 6 random characters (createStaging).
constexpr const char* kStagingSuffix = ".crankcheck-partial-";
constexpr size_t kStagingExtra = 1 + std::char_traits<char>::length(kStagingSuffix) + 6;

// The process's umask (Linux 4.7's "Umask:" line of /proc/self/status), 022 where it cannot be read.
mode_t readUmask() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("Umask:", 0) == 0) return static_cast<mode_t>(std::strtoul(line.c_str() + 6, nullptr, 8));
  return 022;
}

// A path the file system cannot hold is the user's input, not the environment's failure: refused before any work.
// `extra`: bytes crankcheck adds to the last name (the staging folder's).
void checkNameLengths(const std::string& flag, const fs::path& target, const fs::path& path, size_t extra) {
  if (path.string().size() + extra >= PATH_MAX)
    refuse(flag, target, "a path of " + std::to_string(path.string().size()) + " bytes; the file system takes " +
                             std::to_string(PATH_MAX - 1 - extra) + " here");
  for (const fs::path& name : path) {
    const size_t allowed = NAME_MAX - (name == path.filename() ? extra : 0);
    if (name.string().size() > allowed)
      refuse(flag, target, "a name of " + std::to_string(name.string().size()) + " bytes; the file system takes " +
                               std::to_string(allowed) + " here" +
                               (extra > 0 && name == path.filename() ? " (crankcheck stages the folder beside it "
                                                                       "under a longer name)"
                                                                     : ""));
  }
}

// The innermost folder above `path` (not `path` itself) that holds a crankcheck manifest: a report or shard crankcheck
// wrote; empty if none. Symbolic links in the parents are followed, so a link into a report is seen as in it.
fs::path findEnclosingReport(const fs::path& path) {
  std::error_code ec;
  fs::path resolved = fs::weakly_canonical(path, ec);
  if (ec) resolved = path;
  struct stat st {};
  for (fs::path p = resolved.parent_path(); !p.empty(); p = p.parent_path()) {
    if (::lstat((p / kManifestName).c_str(), &st) == 0) return p;
    if (p == p.root_path()) break;
  }
  return {};
}

void checkNotInsideReport(const std::string& flag, const fs::path& target, const fs::path& path) {
  const fs::path report = findEnclosingReport(path);
  if (!report.empty())
    refuse(flag, target, "is inside " + quotePath(report.string()) +
                             ", a folder crankcheck wrote (it holds crankcheck-manifest.json): writing there would "
                             "make it hold a file crankcheck did not write, and every later run or merge would refuse "
                             "it; choose a place outside it");
}

}  // namespace

FolderManifest readFolderManifest(const fs::path& folder) {
  const fs::path file = folder / kManifestName;
  const std::string where = quotePath(file);
  struct stat st {};
  if (::lstat(file.c_str(), &st) != 0) throw std::runtime_error(where + ": missing");
  if (!S_ISREG(st.st_mode)) throw std::runtime_error(where + ": not a plain file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(where + ": cannot be read");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(where + ": not JSON (" + escapeText(e.what()) + ")");
  }
  FolderManifest m;
  try {
    if (!j.is_object() || !j.contains("tool") || j["tool"] != "crankcheck")
      throw std::runtime_error(where + ": not crankcheck's (its \"tool\" is not \"crankcheck\")");
    m.version = j.at("version").get<std::string>();
    m.kind = j.at("kind").get<std::string>();
    std::set<std::string> seen;
    for (const nlohmann::json& f : j.at("files")) {
      if (f.is_string())
        throw std::runtime_error(where + ": lists " + quotePath(f.get<std::string>()) + " without its size and checksum "
                                 "(an earlier crankcheck's record, which cannot tell a file it wrote from one changed "
                                 "since; remove the folder yourself or write elsewhere)");
      ManifestFile entry;
      entry.path = f.at("path").get<std::string>();
      const std::string why = whyNotInside(entry.path);
      if (!why.empty())
        throw std::runtime_error(where + ": lists " + quotePath(entry.path) + ", " + why + ", not a file inside the folder");
      if (!seen.insert(entry.path).second) throw std::runtime_error(where + ": lists " + quotePath(entry.path) + " twice");
      if (!f.at("size").is_number_unsigned())
        throw std::runtime_error(where + ": " + quotePath(entry.path) + ": its size is not a count of bytes");
      entry.size = f.at("size").get<std::uintmax_t>();
      entry.crc32 = f.at("crc32").get<std::string>();
      if (entry.crc32.size() != 8 || entry.crc32.find_first_not_of("0123456789abcdef") != std::string::npos)
        throw std::runtime_error(where + ": " + quotePath(entry.path) + ": its crc32 is not 8 lower-case hex digits");
      m.files.push_back(std::move(entry));
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(where + ": malformed (" + escapeText(e.what()) + ")");
  }
  return m;
}

bool isAsRecorded(const fs::path& folder, const ManifestFile& file) {
  const auto [fd, dir] = openInside(folder, file.path);
  if (fd < 0) return false;
  const bool ours = matchesRecord(fd, file);
  ::close(fd);
  ::close(dir);
  return ours;
}

void checkOutputFolder(const fs::path& target, const std::string& flag) {
  if (target.empty()) throw UsageError(flag + ": must name a folder");
  const fs::path path = normalTarget(target);
  checkNameLengths(flag, target, path, kStagingExtra);
  checkNotInsideReport(flag, target, path);
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    if (errno == ENOTDIR) refuse(flag, target, "a part of the path is a file, not a folder");
    throw EnvironmentError(flag + ": " + quotePath(target) + ": cannot be examined: " + std::strerror(errno));
  }
  if (S_ISLNK(st.st_mode))
    refuse(flag, target, std::string("is a symbolic link; crankcheck does not write through links (") + kRule + ")");
  if (!S_ISDIR(st.st_mode))
    refuse(flag, target, std::string("is a file, not a folder; crankcheck never overwrites it (") + kRule + ")");
  std::error_code ec;
  if (fs::is_empty(path, ec) && !ec) return;
  // The manifest, if the folder has one: what it names is judged file by file below; a manifest that names anything
  // but a file inside the folder, as crankcheck records them, makes the folder not crankcheck's.
  std::map<std::string, ManifestFile> listed;
  bool has_manifest = false;
  if (::lstat((path / kManifestName).c_str(), &st) == 0 && S_ISREG(st.st_mode)) {
    try {
      for (ManifestFile& f : readFolderManifest(path).files) listed.emplace(f.path, std::move(f));
      has_manifest = true;
    } catch (const std::runtime_error& e) {
      refuse(flag, target, std::string(e.what()) + "; nothing was changed, nothing it names was touched (" + kRule + ")");
    }
  }
  try {
    // Each entry is judged as the walk reaches it, before the walk descends into it: the first one crankcheck did
    // not write ends the check (`--out /` or `--out ~` is refused at its first entry, nothing below it is read).
    for (auto it = fs::recursive_directory_iterator(path); it != fs::recursive_directory_iterator(); ++it) {
      const fs::directory_entry& entry = *it;
      const std::string rel = entry.path().lexically_relative(path).generic_string();
      const fs::file_status status = entry.symlink_status();
      bool ours = false;
      if (has_manifest) {
        if (fs::is_regular_file(status)) {
          const auto file = listed.find(rel);
          if (file != listed.end() && !isAsRecorded(path, file->second))
            refuse(flag, target, "holds " + quotePath(rel) + ", changed since crankcheck wrote it (not the size and "
                                 "checksum its manifest records); nothing was changed (" + kRule + ")");
          ours = rel == kManifestName || file != listed.end();
        } else if (fs::is_directory(status)) {
          ours = parentsListed(rel, listed);
        }
      }
      if (!ours)
        refuse(flag, target,
               "holds " + quotePath(rel) + ", which crankcheck did not write; nothing was changed (" + kRule + ")");
    }
  } catch (const fs::filesystem_error& e) {
    throw EnvironmentError(flag + ": " + quotePath(target) + ": cannot be examined: " + e.code().message());
  }
}

void checkNewFile(const fs::path& file, const std::string& flag, const std::vector<fs::path>& outputs) {
  if (file.empty()) throw UsageError(flag + ": must name a file");
  const fs::path path = normalTarget(file);
  checkNameLengths(flag, file, path, 0);
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0)
    refuse(flag, file, S_ISLNK(st.st_mode) ? "is a symbolic link (to a file or not); crankcheck never writes through a link"
                                          : "exists; crankcheck never overwrites a file");
  if (errno == ENOTDIR) refuse(flag, file, "a part of the path is a file, not a folder");
  if (!fs::is_directory(path.parent_path())) refuse(flag, file, "its folder does not exist");
  checkNotInsideReport(flag, file, path);
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(path, ec);
  for (const fs::path& output : outputs) {
    const fs::path folder = fs::weakly_canonical(normalTarget(output), ec);
    const auto [end, _] = std::mismatch(folder.begin(), folder.end(), resolved.begin(), resolved.end());
    if (end == folder.end())
      refuse(flag, file, "is inside the output folder " + quotePath(output) +
                             ", which holds only what crankcheck writes there; choose a place outside it");
  }
}

void writeNewFile(const fs::path& path, std::string_view content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) throw EnvironmentError(quotePath(path) + ": cannot write: " + std::strerror(errno));
  // The file is ours (O_EXCL made it): a write that fails removes it, so that no empty or cut file is left for the
  // next run to refuse as "exists".
  auto fail = [&](int error) {
    ::unlink(path.c_str());
    throw EnvironmentError(quotePath(path) + ": cannot write: " + std::strerror(error));
  };
  size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      ::close(fd);
      fail(error);
    }
    done += static_cast<size_t>(n);
  }
  if (::close(fd) != 0) fail(errno);
}

OutputFolder::OutputFolder(fs::path target, std::string flag) : target_(std::move(target)), flag_(std::move(flag)) {
  checkOutputFolder(target_, flag_);
}

OutputFolder::~OutputFolder() { abandon(); }

void OutputFolder::createStaging() {
  std::lock_guard<std::mutex> lock(mutex_);
  const fs::path path = normalTarget(target_);
  std::vector<fs::path> missing;
  struct stat st {};
  for (fs::path p = path.parent_path(); ::lstat(p.c_str(), &st) != 0 && errno == ENOENT; p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.root_path()) break;
  }
  std::reverse(missing.begin(), missing.end());
  for (const fs::path& p : missing) {
    if (::mkdir(p.c_str(), 0777) != 0) {
      const int error = errno;
      for (auto it = created_parents_.rbegin(); it != created_parents_.rend(); ++it) ::rmdir(it->c_str());
      created_parents_.clear();
      if (error == ENOTDIR) refuse(flag_, target_, "a part of the path is a file, not a folder");
      throw EnvironmentError(flag_ + ": " + quotePath(p) + ": cannot create the folder: " + std::strerror(error));
    }
    created_parents_.push_back(p);
  }
  std::string name = (path.parent_path() / ("." + path.filename().string() + kStagingSuffix + "XXXXXX")).string();
  if (::mkdtemp(name.data()) == nullptr) {
    const int error = errno;
    for (auto it = created_parents_.rbegin(); it != created_parents_.rend(); ++it) ::rmdir(it->c_str());
    created_parents_.clear();
    throw EnvironmentError(flag_ + ": " + quotePath(target_) + ": cannot write beside it: " + std::strerror(error));
  }
  // mkdtemp makes the folder 0700; the report is the user's, readable as any folder they make (mode 0777 less the
  // process's umask, read from /proc without changing it: another thread may be creating files meanwhile).
  ::chmod(name.c_str(), 0777 & ~readUmask());
  staging_ = name;
}

void OutputFolder::install(const std::string& kind) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (staging_.empty() || installed_) throw std::logic_error("OutputFolder::install: nothing staged");
  std::vector<std::string> paths;
  for (const fs::directory_entry& entry : entriesUnder(staging_))
    if (entry.symlink_status().type() == fs::file_type::regular)
      paths.push_back(entry.path().lexically_relative(staging_).generic_string());
  std::sort(paths.begin(), paths.end());
  nlohmann::json files = nlohmann::json::array();
  for (const std::string& rel : paths) {
    std::ifstream in(staging_ / rel, std::ios::binary);
    std::ostringstream content;
    content << in.rdbuf();
    if (!in) throw EnvironmentError(quotePath(staging_ / rel) + ": cannot read back what was written");
    const std::string bytes = content.str();
    files.push_back({{"path", rel}, {"size", bytes.size()}, {"crc32", calcManifestChecksum(bytes)}});
  }
  const nlohmann::json manifest = {{"tool", "crankcheck"}, {"version", getCrankcheckVersion()}, {"kind", kind}, {"files", files}};
  writeNewFile(staging_ / kManifestName, manifest.dump(2) + "\n");

  // Once more: the folder may have changed while the campaign ran (a file of the user's put in it, a listed file
  // edited). The run's work is not thrown away for that: the new report is installed all the same, and what was
  // there is moved aside whole (removePreviousReport removes only the files crankcheck wrote, as it wrote them, and
  // keeps the rest as TARGET.previous, named in a warning). Nothing of the user's is removed either way. A target
  // that is no longer a folder (a link, a file put in its place) is refused as before: nothing is swapped with it.
  const fs::path path = normalTarget(target_);
  struct stat st {};
  try {
    checkOutputFolder(target_, flag_);
  } catch (const UsageError&) {
    if (::lstat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) throw;
  }
  if (::lstat(path.c_str(), &st) != 0) {
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, path.c_str(), RENAME_NOREPLACE) != 0)
      throw EnvironmentError(flag_ + ": " + quotePath(target_) + ": cannot install the report: " + std::strerror(errno));
  } else {
    // Swap the two folders in one step (Linux renameat2): a reader sees the old report or the new one.
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, path.c_str(), RENAME_EXCHANGE) != 0)
      throw EnvironmentError(flag_ + ": " + quotePath(target_) + ": cannot replace the previous report: " +
                             std::strerror(errno));
    old_ = staging_;
  }
  installed_ = true;
  staging_.clear();
  created_parents_.clear();
  if (!old_.empty()) removePreviousReport(old_, target_);
  old_.clear();
}

fs::path removePreviousReport(const fs::path& old_folder, const fs::path& target) {
  // Only a plain file the old manifest lists, as it records it, is removed (then the manifest and the emptied
  // folders); anything else stays, and is named.
  std::string unread;                // why the manifest could not be read: then nothing is removed
  std::set<std::string> unremovable;  // files as crankcheck wrote them that could not be removed (permissions)
  struct stat folder {};
  if (::lstat(old_folder.c_str(), &folder) != 0) return {};
  const bool real_folder = S_ISDIR(folder.st_mode);  // a link is never walked: only moved aside below
  if (!real_folder) unread = "not a folder";
  if (real_folder) try {
    const FolderManifest manifest = readFolderManifest(old_folder);
    struct stat st {};
    for (const ManifestFile& f : manifest.files)
      if (!removeIfAsRecorded(old_folder, f) && isAsRecorded(old_folder, f)) unremovable.insert(f.path);
    if (::lstat((old_folder / kManifestName).c_str(), &st) == 0 && S_ISREG(st.st_mode))
      ::unlink((old_folder / kManifestName).c_str());
  } catch (const std::runtime_error& e) {
    unread = e.what();
  }
  std::error_code ec;
  std::vector<fs::path> dirs;
  for (auto it = fs::recursive_directory_iterator(old_folder, ec); real_folder && !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->symlink_status(ec).type() == fs::file_type::directory) dirs.push_back(it->path());
  std::sort(dirs.begin(), dirs.end(), [](const fs::path& a, const fs::path& b) { return a.string() > b.string(); });
  for (const fs::path& d : dirs) ::rmdir(d.c_str());
  if (real_folder && (::rmdir(old_folder.c_str()) == 0 || errno == ENOENT)) return {};
  std::vector<std::string> kept, stuck;  // what remains but folders, in order: not crankcheck's; crankcheck's as written
  for (auto it = fs::recursive_directory_iterator(old_folder, ec); real_folder && !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->symlink_status(ec).type() != fs::file_type::directory) {
      const std::string rel = it->path().lexically_relative(old_folder).generic_string();
      if (rel == kManifestName) continue;
      (unremovable.count(rel) ? stuck : kept).push_back(rel);
    }
  std::sort(kept.begin(), kept.end());
  std::sort(stuck.begin(), stuck.end());
  // What remains is the user's: moved from the hidden staging name to one that says what it is, never over a path.
  fs::path kept_at = old_folder;
  const fs::path normal = normalTarget(target);
  for (int i = 1; i <= 99; ++i) {
    const fs::path visible = normal.string() + ".previous" + (i == 1 ? "" : "-" + std::to_string(i));
    if (::renameat2(AT_FDCWD, old_folder.c_str(), AT_FDCWD, visible.c_str(), RENAME_NOREPLACE) == 0) {
      kept_at = visible;
      break;
    }
    if (errno != EEXIST) break;
  }
  auto name = [](const std::vector<std::string>& files) {
    std::string named;
    for (size_t i = 0; i < files.size() && i < 3; ++i) named += (i ? ", " : " (") + quotePath(files[i]);
    return files.empty() ? named : named + (files.size() > 3 ? ", ...)" : ")");
  };
  std::string why;
  if (!unread.empty()) why = "its manifest cannot be read (" + escapeText(unread) + "), so nothing of it was removed";
  if (unread.empty() && !kept.empty()) why = "it holds files crankcheck did not write or that changed since" + name(kept);
  if (unread.empty() && !stuck.empty())
    why += (why.empty() ? "" : "; and ") + std::string("files crankcheck wrote, unchanged, could not be removed") +
           name(stuck) + " (the file system refused)";
  if (why.empty()) why = "it holds folders crankcheck could not remove";
  std::cerr << "crankcheck: warning: " << quotePath(kept_at) << ": the previous report of " << quotePath(target)
            << " was kept there"
            << (kept_at == old_folder ? " (no free name " + quotePath(normal.string() + ".previous") + " beside it)" : "")
            << ": " << why << "\n";
  return kept_at;
}

void OutputFolder::abandon() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!installed_ && !staging_.empty()) {
    std::error_code ec;
    fs::remove_all(staging_, ec);  // the staging folder holds only what this run wrote
    staging_.clear();
    for (auto it = created_parents_.rbegin(); it != created_parents_.rend(); ++it) ::rmdir(it->c_str());
    created_parents_.clear();
  } else if (installed_ && !old_.empty()) {
    removePreviousReport(old_, target_);
    old_.clear();
  }
}

}  // namespace crankcheck::validation
