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
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "crankcheck/validation/errors.h"

#ifndef CRANKCHECK_VERSION
#error "CRANKCHECK_VERSION (the project's version) must be defined by the build"
#endif

namespace crankcheck::validation {
namespace fs = std::filesystem;

const char* getCrankcheckVersion() { return CRANKCHECK_VERSION; }

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

struct Manifest {
  bool valid = false;
  std::set<std::string> files;  // relative, generic form
};

Manifest readManifest(const fs::path& folder) {
  Manifest m;
  std::ifstream in(folder / kManifestName);
  if (!in) return m;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("tool").get<std::string>() != "crankcheck") return m;
    for (const auto& f : j.at("files")) m.files.insert(f.get<std::string>());
    m.valid = true;
  } catch (const nlohmann::json::exception&) {
    m.valid = false;
  }
  return m;
}

// Every entry under `folder`, relative, generic form; no symbolic link followed.
std::vector<fs::directory_entry> entriesUnder(const fs::path& folder) {
  std::vector<fs::directory_entry> entries;
  for (auto it = fs::recursive_directory_iterator(folder); it != fs::recursive_directory_iterator(); ++it)
    entries.push_back(*it);
  return entries;
}

bool parentsListed(const std::string& relative_dir, const std::set<std::string>& files) {
  const std::string prefix = relative_dir + "/";
  return std::any_of(files.begin(), files.end(), [&](const std::string& f) { return f.rfind(prefix, 0) == 0; });
}

// The staging folder's name beside a target NAME: ".NAME" + this + 6 random characters (createStaging).
constexpr const char* kStagingSuffix = ".crankcheck-partial-";
constexpr size_t kStagingExtra = 1 + std::char_traits<char>::length(kStagingSuffix) + 6;

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
  const Manifest manifest = readManifest(path);
  try {
    // Each entry is judged as the walk reaches it, before the walk descends into it: the first one crankcheck did
    // not write ends the check (`--out /` or `--out ~` is refused at its first entry, nothing below it is read).
    for (auto it = fs::recursive_directory_iterator(path); it != fs::recursive_directory_iterator(); ++it) {
      const fs::directory_entry& entry = *it;
      const std::string rel = entry.path().lexically_relative(path).generic_string();
      const fs::file_status status = entry.symlink_status();
      bool ours = false;
      if (manifest.valid) {
        if (fs::is_regular_file(status)) ours = rel == kManifestName || manifest.files.count(rel) > 0;
        else if (fs::is_directory(status)) ours = parentsListed(rel, manifest.files);
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
    refuse(flag, file, "exists; crankcheck never overwrites a file");
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
  staging_ = name;
}

void OutputFolder::install(const std::string& kind) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (staging_.empty() || installed_) throw std::logic_error("OutputFolder::install: nothing staged");
  std::vector<std::string> files;
  for (const fs::directory_entry& entry : entriesUnder(staging_))
    if (entry.is_regular_file()) files.push_back(entry.path().lexically_relative(staging_).generic_string());
  std::sort(files.begin(), files.end());
  const nlohmann::json manifest = {{"tool", "crankcheck"}, {"version", getCrankcheckVersion()}, {"kind", kind}, {"files", files}};
  writeNewFile(staging_ / kManifestName, manifest.dump(2) + "\n");

  checkOutputFolder(target_, flag_);  // once more: the folder may have changed while the campaign ran
  const fs::path path = normalTarget(target_);
  struct stat st {};
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
  if (!old_.empty()) removeOld(old_);
  old_.clear();
}

void OutputFolder::removeOld(const fs::path& old_folder) {
  // Only what the old manifest lists (or an empty folder) is removed; anything else stays, and is named.
  const Manifest manifest = readManifest(old_folder);
  std::error_code ec;
  for (const std::string& rel : manifest.files) {
    const fs::path file = old_folder / rel;
    if (fs::is_regular_file(fs::symlink_status(file, ec))) ::unlink(file.c_str());
  }
  if (manifest.valid) ::unlink((old_folder / kManifestName).c_str());
  std::vector<fs::path> dirs;
  for (auto it = fs::recursive_directory_iterator(old_folder, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->is_directory() && !it->is_symlink()) dirs.push_back(it->path());
  std::sort(dirs.begin(), dirs.end(), [](const fs::path& a, const fs::path& b) { return a.string() > b.string(); });
  for (const fs::path& d : dirs) ::rmdir(d.c_str());
  if (::rmdir(old_folder.c_str()) != 0 && errno != ENOENT)
    std::cerr << "crankcheck: warning: " << quotePath(old_folder)
              << ": the previous report was kept there: it holds files crankcheck did not write\n";
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
    removeOld(old_);
    old_.clear();
  }
}

}  // namespace crankcheck::validation
