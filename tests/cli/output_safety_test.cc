// crankcheck is safe to point anywhere (issue 10): it never deletes or overwrites what it did not write, starts
// no shell, checks before it works, exits with one status per meaning, and cleans up when it is interrupted.
// Every test compares the disk before and after, byte for byte.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/output_folder.h"
#include "crankcheck/validation/report_document.h"
#include "run_cli.h"
#include "../support/read_file.h"

namespace crankcheck {
namespace {
namespace fs = std::filesystem;
using validation::ProgramResult;

using testing::readFile;

void writeFile(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// Everything under `dir`: relative path -> file content, "<folder>" or "<link to TARGET>". No link is followed.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    const std::string rel = it->path().lexically_relative(dir).string();
    if (it->is_symlink()) out[rel] = "<link to " + fs::read_symlink(it->path()).string() + ">";
    else if (it->is_directory()) out[rel] = "<folder>";
    else out[rel] = readFile(it->path());
  }
  return out;
}

size_t lines(const std::string& s) { return static_cast<size_t>(std::count(s.begin(), s.end(), '\n')); }

// `run`'s result with the file size limit at `bytes` (as a full disk: a write past it fails with EFBIG), the limit and
// the handler restored after. SIGXFSZ is ignored in the test's own process only: crankcheck starts with its default
// disposition (startProgram resets it), which kills a process at the limit unless it ignores SIGXFSZ itself, as
// crankcheck does (a cut file and a partial folder were left, status 153, no message).
template <class Run>
ProgramResult runWithFileSizeLimit(rlim_t bytes, Run run) {
  rlimit old_limit{};
  if (::getrlimit(RLIMIT_FSIZE, &old_limit) != 0) throw std::runtime_error("getrlimit failed");
  const rlimit small{bytes, old_limit.rlim_max};
  auto old_handler = ::signal(SIGXFSZ, SIG_IGN);
  if (::setrlimit(RLIMIT_FSIZE, &small) != 0) throw std::runtime_error("setrlimit failed");
  const ProgramResult r = run();
  ::setrlimit(RLIMIT_FSIZE, &old_limit);
  ::signal(SIGXFSZ, old_handler);
  return r;
}

class OutputSafetyTest : public ::testing::Test {
 protected:
  // A refusal: status 2, one line in the form "crankcheck: FLAG: ...", nothing on stdout, the disk unchanged.
  void expectRefused(const std::vector<std::string>& args, const std::string& expected,
                     const std::string& flag = "--out") {
    const auto before = snapshot(dir_);
    const ProgramResult r = testing::runCrankcheck(args);
    EXPECT_EQ(r.exit_status, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("crankcheck: " + flag + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(snapshot(dir_), before) << "nothing changed on disk";
  }

  // A shard of a small campaign (one example scene, one report part, --quick; no figures: a fraction of a second)
  // written to `out`: what these tests check is where it is written, not what.
  ProgramResult writeShard(const fs::path& out, const std::string& which = "0/2") {
    return testing::runCrankcheck({"validate", "--quick", (fs::path(CRANKCHECK_SCENES_DIR) / "single_cylinder.toml").string(),
                                   "--parts", "norton_fig13_8", "--shard", which, "--out", out.string()});
  }

  // Whether a run's staging folder appears in the test's folder within 5 s (the campaign has started): what a test
  // that acts mid-run waits for, not a time.
  bool waitForStaging() const {
    for (int i = 0; i < 500; ++i) {
      for (const auto& entry : fs::directory_iterator(dir_))
        if (entry.path().filename().string().find(".crankcheck-partial-") != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

  testing::FreshFolder folder_;  // made for this test alone, removed with what the test wrote
  const fs::path dir_ = folder_.path();
};

TEST_F(OutputSafetyTest, RefusesAFolderHoldingAUsersFile) {
  fs::create_directories(dir_ / "thesis");
  writeFile(dir_ / "thesis/thesis.tex", "\\documentclass{article}\n");
  expectRefused({"validate", "--quick", "--out", (dir_ / "thesis").string()}, "\"thesis.tex\", which crankcheck did not write");
  // The same folder given as "." from inside it (a user's working folder), and with a trailing slash.
  const ProgramResult dot = testing::runCrankcheck({"validate", "--quick", "--out", "."}, {}, dir_ / "thesis");
  EXPECT_EQ(dot.exit_status, 2) << dot.err;
  expectRefused({"validate", "--quick", "--out", (dir_ / "thesis").string() + "/"}, "thesis.tex");
}

TEST_F(OutputSafetyTest, RefusesAPlainFileAndASymbolicLink) {
  writeFile(dir_ / "notes.txt", "mine\n");
  expectRefused({"validate", "--quick", "--out", (dir_ / "notes.txt").string()}, "is a file, not a folder");
  fs::create_directories(dir_ / "elsewhere");
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "link");
  expectRefused({"validate", "--quick", "--out", (dir_ / "link").string()}, "is a symbolic link");
  expectRefused({"validate", "--quick", "--out", (dir_ / "notes.txt/report").string()}, "a part of the path is a file");
}

// A folder that looks like a report but holds one more file (or a link) is not crankcheck's alone: refused.
TEST_F(OutputSafetyTest, ReplacesOnlyAReportItWroteItself) {
  const fs::path shard = dir_ / "shard";
  ASSERT_EQ(writeShard(shard).exit_status, 0);
  const std::string manifest = readFile(shard / "crankcheck-manifest.json");
  EXPECT_NE(manifest.find("\"tool\": \"crankcheck\""), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("\"data/crosscheck.csv\""), std::string::npos) << manifest;
  // Its own report is replaced: a second run succeeds and leaves nothing beside it.
  ASSERT_EQ(writeShard(shard).exit_status, 0);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
  // A user's file inside it, or a link, makes it the user's.
  writeFile(shard / "data/my_notes.txt", "mine\n");
  expectRefused({"validate", "--quick", "--shard", "0/2", "--out", shard.string()}, "\"data/my_notes.txt\"");
  fs::remove(shard / "data/my_notes.txt");
  fs::create_symlink("/etc/passwd", shard / "index.md");
  expectRefused({"validate", "--quick", "--shard", "0/2", "--out", shard.string()}, "\"index.md\"");
  fs::remove(shard / "index.md");
  // `report merge --out` follows the same rule.
  ASSERT_EQ(writeShard(dir_ / "shard1", "1/2").exit_status, 0);
  fs::create_directories(dir_ / "mine");
  writeFile(dir_ / "mine/data.csv", "1,2\n");
  expectRefused({"report", "merge", shard.string(), (dir_ / "shard1").string(), "--out", (dir_ / "mine").string()},
                "\"data.csv\"");
}

// A folder full of other things (`--out /`, `--out ~`) is refused at the first entry crankcheck did not write, with
// status 2 and nothing below that entry read: the walk used to go on into /proc and end with "permission denied"
// (status 3), and walked a whole home folder before refusing.
TEST_F(OutputSafetyTest, RefusesAFolderOfOtherThingsAtItsFirstEntry) {
  for (const std::string root : {"/", "/proc", "/usr"}) {
    const ProgramResult r = testing::runCrankcheck({"validate", "--quick", "--out", root});
    EXPECT_EQ(r.exit_status, 2) << root << ": " << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("crankcheck: --out: \"" + root + "\": holds ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("which crankcheck did not write"), std::string::npos) << r.err;
  }
}

TEST_F(OutputSafetyTest, AnEmptyFolderIsUsed) {
  fs::create_directories(dir_ / "empty");
  const ProgramResult r = writeShard(dir_ / "empty");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "empty/crankcheck-manifest.json"));
}

// Issue 58: a folder can come from anyone (a copied report, a shard from another machine, a hand edit), so what its
// manifest names is never trusted past the folder: a manifest listing a path outside it (`../victim.txt`, an absolute
// path, a path through a link) made the next run into that folder delete that file, with status 0. Each such folder
// is refused before any work (status 2, one line naming the entry) and every file, inside and outside, stays.
class ForeignManifestTest : public OutputSafetyTest {
 protected:
  // A report folder `name` holding index.md (its record right) and a manifest that also lists `entry`.
  fs::path writeReport(const std::string& name, const std::string& entry_json) {
    const fs::path report = dir_ / name;
    fs::create_directories(report);
    writeFile(report / "index.md", "the previous report\n");
    writeFile(report / "crankcheck-manifest.json",
              R"({"tool": "crankcheck", "version": "0.2.0", "kind": "report", "files": [)"
              R"({"path": "index.md", "size": 20, "crc32": "b1d3fb7f"}, )" + entry_json + "]}");
    return report;
  }
  // Every way into a folder: validate, grade, a shard's run and report merge.
  void expectEveryCommandRefuses(const fs::path& report, const std::string& expected) {
    const std::string scene = (fs::path(CRANKCHECK_SCENES_DIR) / "single_cylinder.toml").string();
    expectRefused({"validate", "--quick", scene, "--parts", "norton_fig13_8", "--out", report.string()}, expected);
    expectRefused({"validate", "--quick", scene, "--parts", "norton_fig13_8", "--shard", "0/2", "--out",
                   report.string()}, expected);
    expectRefused({"grade", "--quick", "--out", report.string(), "--", "/bin/false"}, expected);
    // Two shards of their own for each folder (the test's folder, removed with what the test wrote, holds them).
    const fs::path s0 = dir_ / (report.filename().string() + "-s0"), s1 = dir_ / (report.filename().string() + "-s1");
    ASSERT_EQ(writeShard(s0, "0/2").exit_status, 0);
    ASSERT_EQ(writeShard(s1, "1/2").exit_status, 0);
    expectRefused({"report", "merge", s0.string(), s1.string(), "--out", report.string()}, expected);
  }
};

TEST_F(ForeignManifestTest, AManifestNamingAPathOutsideIsRefusedAndNothingIsTouched) {
  writeFile(dir_ / "victim.txt", "a user's file\n");
  const std::string victim = R"({"path": "../victim.txt", "size": 14, "crc32": "00000000"})";
  expectEveryCommandRefuses(writeReport("dotdot", victim), "lists \"../victim.txt\", a path through \"..\"");
  const std::string absolute = R"({"path": ")" + (dir_ / "victim.txt").string() + R"(", "size": 14, "crc32": "00000000"})";
  expectEveryCommandRefuses(writeReport("absolute", absolute), "an absolute path");
  EXPECT_EQ(readFile(dir_ / "victim.txt"), "a user's file\n");
}

// A listed path through a symbolic link inside the folder, or a listed file changed since (its size or checksum
// not the one recorded), is not crankcheck's: refused, the link's target and the edited file kept.
TEST_F(ForeignManifestTest, AListedFileThroughALinkOrChangedSinceIsRefused) {
  fs::create_directories(dir_ / "elsewhere");
  writeFile(dir_ / "elsewhere/victim.txt", "a user's file\n");
  const fs::path linked = writeReport("linked", R"({"path": "data/victim.txt", "size": 14, "crc32": "00000000"})");
  fs::create_directory_symlink(dir_ / "elsewhere", linked / "data");
  expectEveryCommandRefuses(linked, "\"data\", which crankcheck did not write");
  const fs::path edited = writeReport("edited", R"({"path": "notes.md", "size": 5, "crc32": "00000000"})");
  writeFile(edited / "notes.md", "mine\n");  // 5 bytes, another checksum: a user's edit
  expectEveryCommandRefuses(edited, "\"notes.md\", changed since crankcheck wrote it");
  EXPECT_EQ(readFile(dir_ / "elsewhere/victim.txt"), "a user's file\n");
}

// An earlier crankcheck's manifest (a list of names, no sizes or checksums) cannot tell its files from a user's
// edit: refused with that reason, the folder left as it is.
TEST_F(ForeignManifestTest, AManifestWithoutChecksumsIsRefused) {
  const fs::path report = dir_ / "old";
  fs::create_directories(report);
  writeFile(report / "index.md", "the previous report\n");
  writeFile(report / "crankcheck-manifest.json",
            R"({"tool": "crankcheck", "version": "0.1.0", "kind": "report", "files": ["index.md"]})");
  expectRefused({"validate", "--quick", "--out", report.string()}, "without its size and checksum");
}

// crankcheck's own report is still replaced, and the manifest it writes records each file's size and CRC-32, as
// computed here from the bytes on disk (zlib's CRC-32, by Python, outside crankcheck).
TEST_F(ForeignManifestTest, ItsOwnReportIsReplacedAndItsRecordMatchesTheFiles) {
  const fs::path shard = dir_ / "shard";
  ASSERT_EQ(writeShard(shard).exit_status, 0);
  validation::ProgramCall call{{"/usr/bin/python3", "-c",
                                "import json, os, sys, zlib\n"
                                "d = sys.argv[1]; m = json.load(open(os.path.join(d, 'crankcheck-manifest.json')))\n"
                                "for f in m['files']:\n"
                                "    b = open(os.path.join(d, f['path']), 'rb').read()\n"
                                "    assert f['size'] == len(b) and f['crc32'] == '%08x' % zlib.crc32(b), f\n"
                                "print(len(m['files']))\n",
                                shard.string()}};
  call.timeout_seconds = testing::kCliRunSeconds;
  const ProgramResult check = validation::runProgram(call);
  ASSERT_EQ(check.exit_status, 0) << check.err;
  EXPECT_GE(std::stoi(check.out), 3) << check.out;
  ASSERT_EQ(writeShard(shard).exit_status, 0);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

// A missing gnuplot is found before the campaign: the full campaign takes about 20 s, the refusal comes at once
// (2 s is 100 x crankcheck's start-up, and a tenth of the campaign), with status 3 and nothing written.
TEST_F(OutputSafetyTest, MissingGnuplotIsFoundBeforeAnyWork) {
  fs::create_directories(dir_ / "bin");  // PATH holds only this empty folder
  const auto start = std::chrono::steady_clock::now();
  const ProgramResult r = testing::runCrankcheck({"validate", "--out", (dir_ / "report").string()},
                                                 {"PATH=" + (dir_ / "bin").string()});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_status, 3) << r.err;
  EXPECT_NE(r.err.find("crankcheck: gnuplot: not found on PATH"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_LT(seconds, 2.0);
  EXPECT_EQ(snapshot(dir_), (std::map<std::string, std::string>{{"bin", "<folder>"}}));
}

// A gnuplot that never answers (here a stand-in on PATH that writes its process id and sleeps) is ended at
// kGnuplotVersionSeconds and crankcheck stops before any work: status 3, one line, nothing written, the child gone.
class HangingGnuplotTest : public OutputSafetyTest {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "bin");
    const fs::path fake = dir_ / "bin/gnuplot";
    writeFile(fake, "#!/bin/sh\necho $$ > '" + (dir_ / "gnuplot.pid").string() + "'\nexec /bin/sleep 600\n");
    fs::permissions(fake, fs::perms::owner_all);
  }
  // The stand-in's process id, once it has started (at most 20 s: crankcheck starts it before any work).
  pid_t waitForGnuplot() {
    for (int i = 0; i < 2000; ++i) {
      std::ifstream in(dir_ / "gnuplot.pid");
      pid_t pid = 0;
      if (in >> pid && pid > 0) return pid;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return 0;
  }
  // Whether `pid` still runs (a zombie left to the system's reaper has ended), waiting up to 5 s for it to end.
  static bool stillRuns(pid_t pid) {
    for (int i = 0; i < 500; ++i) {
      std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
      std::string stat;
      if (!std::getline(in, stat)) return false;
      const size_t close = stat.rfind(')');
      if (close != std::string::npos && close + 2 < stat.size() && stat[close + 2] == 'Z') return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
  }
  std::vector<std::string> path() const { return {"PATH=" + (dir_ / "bin").string()}; }
};

TEST_F(HangingGnuplotTest, IsEndedAtItsTimeLimit) {
  const ProgramResult r = testing::runCrankcheck({"validate", "--quick", "--out", (dir_ / "report").string()}, path());
  EXPECT_EQ(r.exit_status, 3) << r.err;
  EXPECT_EQ(r.err, "crankcheck: gnuplot: 'gnuplot --version' did not answer within 10 s; gnuplot was ended\n");
  EXPECT_EQ(r.out, "");
  const pid_t gnuplot = waitForGnuplot();
  ASSERT_GT(gnuplot, 0);
  EXPECT_FALSE(stillRuns(gnuplot));
  EXPECT_FALSE(fs::exists(dir_ / "report"));
}

// SIGTERM, SIGINT or SIGHUP while crankcheck waits on a child (before any output folder exists): status 128 + the
// signal, and the child does not outlive crankcheck.
class SignalWhileWaitingTest : public HangingGnuplotTest, public ::testing::WithParamInterface<int> {};

TEST_P(SignalWhileWaitingTest, EndsTheChildWithCrankcheck) {
  validation::ProgramCall call{{CRANKCHECK_BINARY, "validate", "--quick", "--out", (dir_ / "report").string()}, {}, path()};
  call.timeout_seconds = testing::kCliRunSeconds;
  validation::RunningProgram run = validation::startProgram(call);
  const pid_t gnuplot = waitForGnuplot();
  ASSERT_GT(gnuplot, 0) << "crankcheck never started gnuplot";
  ASSERT_EQ(::kill(run.pid(), GetParam()), 0);
  const ProgramResult r = run.wait();
  EXPECT_EQ(r.exit_status, 128 + GetParam()) << r.err;
  // One line, from its first byte: stderr is a pipe here, not a terminal that echoed ^C (a blank line came first).
  EXPECT_EQ(r.err.rfind("crankcheck: interrupted by ", 0), 0u) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_FALSE(stillRuns(gnuplot)) << "gnuplot (pid " << gnuplot << ") outlived crankcheck";
  EXPECT_FALSE(fs::exists(dir_ / "report"));
}
INSTANTIATE_TEST_SUITE_P(Signals, SignalWhileWaitingTest, ::testing::Values(SIGINT, SIGTERM, SIGHUP),
                         [](const auto& info) {
                           return info.param == SIGINT ? "SIGINT" : info.param == SIGTERM ? "SIGTERM" : "SIGHUP";
                         });

// A write that fails (here: the file-size limit, which refuses writes as a full disk does, even to root) is the
// environment's failure: status 3, the file named, the previous report as it was, no partial folder left.
TEST_F(OutputSafetyTest, AFailedWriteIsStatus3AndKeepsThePreviousReport) {
  const fs::path shard = dir_ / "shard";
  ASSERT_EQ(writeShard(shard).exit_status, 0);
  const auto before = snapshot(dir_);
  // Every table of a shard is larger than 1 KiB.
  const ProgramResult r = runWithFileSizeLimit(1024, [&] { return writeShard(shard); });
  EXPECT_EQ(r.exit_status, 3) << r.err;
  EXPECT_NE(r.err.find(": cannot write: File too large"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_EQ(snapshot(dir_), before);
}

// Issue 46: where a run would write into a report crankcheck wrote (a profile or an --out inside it, a profile in the
// run's own --out), the report then held a file crankcheck did not write and refused every later run or merge; and
// a name the file system cannot hold ended with status 3 after the check. All refused before any work, status 2.
TEST_F(OutputSafetyTest, NothingIsWrittenInsideAReportOrUnderANameTooLong) {
  const fs::path shard = dir_ / "shard", other = dir_ / "other";
  ASSERT_EQ(writeShard(shard).exit_status, 0);
  ASSERT_EQ(writeShard(other, "1/2").exit_status, 0);
  const std::string scene = (fs::path(CRANKCHECK_SCENES_DIR) / "single_cylinder.toml").string();
  auto validate = [&](const fs::path& out, const fs::path& profile) {
    return std::vector<std::string>{"validate", "--quick", scene, "--parts", "norton_fig13_8", "--shard", "0/2",
                                    "--out", out.string(), "--profile", profile.string()};
  };
  const std::string inside = "a folder crankcheck wrote (it holds crankcheck-manifest.json)";
  // The profile inside the --out report being replaced, inside another report, or the --out folder itself.
  expectRefused(validate(shard, shard / "profile.csv"), inside, "--profile");
  expectRefused(validate(dir_ / "new", other / "data" / "profile.csv"), inside, "--profile");
  expectRefused(validate(dir_ / "new", dir_ / "new"), "is inside the output folder", "--profile");
  expectRefused(validate(dir_ / "new", dir_ / "new" / "p.csv"), "", "--profile");
  // --out inside a report (validate), inside a shard being merged (report merge), through a link into one.
  expectRefused({"validate", "--quick", scene, "--out", (shard / "data" / "new").string()}, inside);
  expectRefused({"report", "merge", shard.string(), other.string(), "--out", (other / "data" / "new").string()}, inside);
  fs::create_directory_symlink(shard / "data", dir_ / "link");
  expectRefused({"validate", "--quick", scene, "--out", (dir_ / "link" / "new").string()}, inside);
  // NAME_MAX (255 on Linux) less the staging folder's ".NAME.crankcheck-partial-XXXXXX" (27 more bytes): 228.
  expectRefused({"validate", "--quick", scene, "--out", (dir_ / std::string(229, 'x')).string()}, "a name of 229 bytes");
  expectRefused({"report", "merge", shard.string(), other.string(), "--out", (dir_ / std::string(300, 'x')).string()},
                "a name of 300 bytes");
  expectRefused({"grade", "--quick", "--out", (dir_ / std::string(229, 'x')).string(), "--", "true"}, "a name of 229");
  expectRefused(validate(dir_ / "new", dir_ / std::string(256, 'p')), "a name of 256 bytes", "--profile");
  // Just within: a 228-byte --out is written.
  const ProgramResult longest = writeShard(dir_ / std::string(228, 'x'));
  EXPECT_EQ(longest.exit_status, 0) << longest.err;
}

// Issue 46: a profile that cannot be written (here: past the file size limit, as on a full disk) left an empty file
// that the next run refused as "exists"; the write now removes what it began. Status 3, one line.
TEST_F(OutputSafetyTest, AProfileThatCannotBeWrittenIsRemoved) {
  const std::string scene = (fs::path(CRANKCHECK_SCENES_DIR) / "single_cylinder.toml").string();
  const auto before = snapshot(dir_);
  // 32 bytes: the profile's header line alone is 61; the profile is the first file a shard writes.
  const ProgramResult r = runWithFileSizeLimit(32, [&] {
    return testing::runCrankcheck({"validate", "--quick", scene, "--parts", "norton_fig13_8", "--shard", "0/2", "--out",
                                   (dir_ / "s").string(), "--profile", (dir_ / "profile.csv").string()});
  });
  EXPECT_EQ(r.exit_status, 3) << r.err;
  EXPECT_NE(r.err.find("profile.csv\": cannot write: File too large"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_EQ(snapshot(dir_), before);
}

// Issue 46: results larger than stdio's buffer (4 KiB) written to a full device ended with status 0: the failed
// write was seen only in the stream's error flag. Each command's results to /dev/full: status 3, one line.
TEST(StdoutTest, ResultsThatCannotBeWrittenAreStatus3) {
  const std::string scene = (fs::path(CRANKCHECK_SCENES_DIR) / "inline4_four_stroke.toml").string();
  std::string angles = "0";
  for (int deg = 5; deg < 720; deg += 5) angles += "," + std::to_string(deg);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"eval", scene, "--phi-deg", angles}, {"eval", scene, "--phi-deg", "0"},
        {"balance", scene, "--format", "json"}, {"torsion", scene}}) {
    // The shell here is the test's own fixed words; the program and its arguments are passed as "$@".
    validation::ProgramCall call{{"/bin/sh", "-c", "exec \"$@\" > /dev/full", "sh", CRANKCHECK_BINARY}};
    call.argv.insert(call.argv.end(), args.begin(), args.end());
    call.timeout_seconds = testing::kCliRunSeconds;
    const ProgramResult r = validation::runProgram(call);
    EXPECT_EQ(r.exit_status, 3) << args[0] << ": " << r.err;
    EXPECT_EQ(r.err.rfind("crankcheck: stdout: cannot write the results", 0), 0u) << args[0] << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
  }
}

// A program's stderr is kept to its end (grade quotes its last lines): one that writes 8 MiB to stderr costs
// crankcheck kErrorTailBytes of it (at most twice that while reading), not 8 MiB; a short one is kept whole.
TEST(StderrTest, AProgramsStderrIsKeptToItsEnd) {
  validation::ProgramCall flood{{"/usr/bin/python3", "-c",
                                 "import os\nfor _ in range(8): os.write(2, b'e' * (1 << 20))\nos.write(2, b'last\\n')"}};
  flood.timeout_seconds = testing::kCliRunSeconds;
  const ProgramResult r = validation::runProgram(flood);
  ASSERT_EQ(r.exit_status, 0) << r.err.substr(r.err.size() > 300 ? r.err.size() - 300 : 0);
  EXPECT_TRUE(r.err_cut);
  ASSERT_EQ(r.err.size(), validation::kErrorTailBytes);
  EXPECT_EQ(r.err.substr(r.err.size() - 5), "last\n");
  EXPECT_EQ(r.err.find_first_not_of('e'), r.err.size() - 5);
  validation::ProgramCall short_call{{"/usr/bin/python3", "-c", "import sys\nsys.stderr.write('one\\ntwo\\n')"}};
  short_call.timeout_seconds = testing::kCliRunSeconds;
  const ProgramResult s = validation::runProgram(short_call);
  EXPECT_FALSE(s.err_cut);
  EXPECT_EQ(s.err, "one\ntwo\n");
}

// SIGINT and SIGTERM in the middle of a run: status 128 + the signal, the previous report as it was, the partial
// folder removed. The previous report is a folder crankcheck's manifest marks as its own.
class InterruptTest : public OutputSafetyTest, public ::testing::WithParamInterface<int> {};

TEST_P(InterruptTest, LeavesThePreviousReportAsItWas) {
  const fs::path report = dir_ / "report";
  fs::create_directories(report);
  writeFile(report / "index.md", "the previous report\n");
  // Its size and CRC-32 (zlib's, computed outside crankcheck: python3 -c "zlib.crc32(b'the previous report\n')").
  writeFile(report / "crankcheck-manifest.json",
            R"({"tool": "crankcheck", "version": "0.1.0", "kind": "report",
                "files": [{"path": "index.md", "size": 20, "crc32": "b1d3fb7f"}]})");
  const auto before = snapshot(dir_);
  validation::RunningProgram run = testing::startCrankcheck({"validate", "--quick", "--out", report.string()});
  // Mid-run: the staging folder exists (the campaign has started); the quick campaign takes about 3 s more.
  ASSERT_TRUE(waitForStaging()) << "the run never started";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_EQ(::kill(run.pid(), GetParam()), 0);
  const ProgramResult r = run.wait();
  EXPECT_EQ(r.exit_status, 128 + GetParam()) << r.err;
  EXPECT_NE(r.err.find("interrupted"), std::string::npos) << r.err;
  EXPECT_EQ(snapshot(dir_), before);
}

INSTANTIATE_TEST_SUITE_P(Signals, InterruptTest, ::testing::Values(SIGINT, SIGTERM),
                         [](const auto& info) { return info.param == SIGINT ? "SIGINT" : "SIGTERM"; });

// Paths that a shell would interpret work as they are, as the output folder and as a scene file, and nothing
// else is created anywhere (the run's working folder stays empty: `$(touch owned)` ran nothing).
struct OddName {
  const char* test_name;
  const char* name;
};
void PrintTo(const OddName& odd, std::ostream* os) { *os << odd.test_name; }  // a stable ctest name

class OddPathTest : public OutputSafetyTest, public ::testing::WithParamInterface<OddName> {};

TEST_P(OddPathTest, WorksAsOutputFolderAndScenePath) {
  const std::string name = GetParam().name;
  const fs::path scene = dir_ / (name + ".toml"), out = dir_ / (name + " report");
  fs::copy_file(fs::path(CRANKCHECK_SCENES_DIR) / "single_cylinder.toml", scene);
  fs::create_directories(dir_ / "cwd");
  // One part that draws the scene under its own name (pin_load_polar's panel titles): the path and the name reach
  // the tables, gnuplot and the report; the other parts add nothing to that (and would cost seconds per name).
  const ProgramResult r = testing::runCrankcheck(
      {"validate", "--quick", scene.string(), "--parts", "pin_load_polar", "--out", out.string()}, {}, dir_ / "cwd");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_GT(fs::file_size(out / "index.html"), 1000u);
  EXPECT_GT(fs::file_size(out / "pin_load_polar.png"), 1000u);
  EXPECT_NE(readFile(out / "index.md").find("Scenes"), std::string::npos);
  // The scene is named by its file's stem on one line: a newline in it shown as \n (a backslash and an n), in its
  // section's heading (where a backquote is escaped for Markdown: a heading is text) and in every table.
  std::string shown;
  for (char c : std::string(name)) shown += c == '\n' ? std::string("\\n") : std::string(1, c);
  const std::string heading = validation::escapeMarkdownText(shown);
  EXPECT_NE(readFile(out / "index.md").find("\n### " + heading + ": your engine\n"), std::string::npos);
  // Nowhere on the page is the name Markdown: no link but the page's own (a name "[link](javascript:...)" made one in
  // every table and sentence that named it), the name's text shown as written.
  const std::string html = readFile(out / "index.html");
  EXPECT_EQ(html.find("<a href=\"\""), std::string::npos);
  EXPECT_EQ(html.find("<a href=\"javascript"), std::string::npos);
  // The scene's name is in the data, quoted as CSV requires where it holds a comma or a quote.
  const std::string scenes_csv = readFile(out / "data/scenes.csv");
  const bool quoted = shown.find_first_of(",\"") != std::string::npos;
  std::string expected = shown;
  if (quoted) {
    expected.clear();
    for (char c : shown) expected += c == '"' ? std::string("\"\"") : std::string(1, c);
    expected = "\"" + expected + "\"";
  }
  EXPECT_NE(scenes_csv.find("," + expected + ","), std::string::npos) << scenes_csv;
  std::set<std::string> entries;
  for (const auto& entry : fs::directory_iterator(dir_)) entries.insert(entry.path().filename().string());
  EXPECT_EQ(entries, (std::set<std::string>{"cwd", name + ".toml", name + " report"}));
  EXPECT_TRUE(fs::is_empty(dir_ / "cwd"));
  EXPECT_FALSE(fs::exists(fs::path(CRANKCHECK_SCENES_DIR) / "owned"));
}

INSTANTIATE_TEST_SUITE_P(
    Paths, OddPathTest,
    ::testing::Values(OddName{"space", "my scene"}, OddName{"single_quote", "it's"},
                      OddName{"double_quote", "say \"hi\""}, OddName{"command_substitution", "x'$(touch owned)'"},
                      OddName{"backticks", "a`touch owned`b"}, OddName{"semicolon", "a; touch owned"},
                      OddName{"markdown_link", "[link](javascript:alert(1))"},
                      OddName{"newline", "two\nlines"}, OddName{"comma", "a,b"},
                      OddName{"non_ascii", "Zylinderkopf_\xC3\xA4\xC3\xB6\xC3\xBC_\xE6\x9B\xB2\xE8\xBD\xB4"}),
    [](const auto& info) { return std::string(info.param.test_name); });

// What remains of a previous report after an install (a file of the user's that appeared in it during the run, after
// the last check) is never removed, and never left under the hidden staging name: it is renamed to R.previous
// (R.previous-2 when that is taken, nothing replaced), and the warning names that folder and the file kept. The
// install's exchange is done here by a rename, as renameat2 would leave the folders.
TEST_F(OutputSafetyTest, WhatRemainsOfAPreviousReportIsKeptUnderAVisibleName) {
  const fs::path report = dir_ / "R";
  for (int round = 1; round <= 2; ++round) {
    {
      validation::OutputFolder out(report, "--out");
      out.createStaging();
      validation::writeNewFile(out.getStaging() / "index.md", "the previous report\n");
      out.install("report");
    }
    const fs::path moved = dir_ / ".R.crankcheck-partial-test";
    fs::rename(report, moved);
    writeFile(moved / "mine.txt", "a user's file\n");
    ::testing::internal::CaptureStderr();
    const fs::path kept = validation::removePreviousReport(moved, report);
    const std::string warning = ::testing::internal::GetCapturedStderr();
    const fs::path expected = dir_ / (round == 1 ? "R.previous" : "R.previous-2");
    EXPECT_EQ(kept, expected);
    EXPECT_EQ(snapshot(kept), (std::map<std::string, std::string>{{"mine.txt", "a user's file\n"}}));
    EXPECT_FALSE(fs::exists(moved));
    EXPECT_EQ(warning, "crankcheck: warning: \"" + expected.string() + "\": the previous report of \"" +
                           report.string() + "\" was kept there: it holds files crankcheck did not write or that "
                           "changed since (\"mine.txt\")\n");
  }
  EXPECT_EQ(readFile(dir_ / "R.previous" / "mine.txt"), "a user's file\n");  // the first round's, not replaced
}

// A file of the user's put into the output folder while the run works (after the check before the work) does not
// throw the run away: the new report is installed, and the previous one's remains (the user's file; crankcheck's own
// files, as recorded, are removed) are kept as R.previous, named in a warning, status 0. The test waits for what it
// controls: the staging folder's existence (the quick campaign then takes about 3 s more).
TEST_F(OutputSafetyTest, AFileThatAppearsDuringTheRunIsKeptAndTheNewReportInstalled) {
  const fs::path report = dir_ / "R";
  ASSERT_EQ(writeShard(report).exit_status, 0);
  validation::RunningProgram run = testing::startCrankcheck({"validate", "--quick", "--out", report.string()});
  ASSERT_TRUE(waitForStaging()) << "the run never started";
  writeFile(report / "mine.txt", "a user's file\n");
  const ProgramResult r = run.wait();
  EXPECT_EQ(r.exit_status, 0) << r.err;
  EXPECT_NE(r.err.find("crankcheck: warning: " + quotePath(dir_ / "R.previous") +
                       ": the previous report of " + quotePath(report) +
                       " was kept there: it holds files crankcheck did not write or that changed since (\"mine.txt\")"),
            std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(report / "index.md"));
  EXPECT_FALSE(fs::exists(report / "mine.txt"));
  EXPECT_EQ(snapshot(dir_ / "R.previous"), (std::map<std::string, std::string>{{"mine.txt", "a user's file\n"}}));
}

// A target replaced during the run by a link (to a folder of the user's, holding an empty folder and a file) is
// refused at the install as before the run: nothing is swapped with the link, nothing behind it is touched.
TEST_F(OutputSafetyTest, ATargetThatBecomesALinkDuringTheRunIsRefusedAndLeftAlone) {
  const fs::path report = dir_ / "R", mine = dir_ / "mine";
  ASSERT_EQ(writeShard(report).exit_status, 0);
  fs::create_directories(mine / "empty");
  writeFile(mine / "notes.txt", "a user's file\n");
  validation::RunningProgram run = testing::startCrankcheck({"validate", "--quick", "--out", report.string()});
  ASSERT_TRUE(waitForStaging()) << "the run never started";
  fs::rename(report, dir_ / "R.moved-by-the-user");
  fs::create_directory_symlink(mine, report);
  const auto before = snapshot(mine);
  const ProgramResult r = run.wait();
  EXPECT_EQ(r.exit_status, 2) << r.err;
  EXPECT_TRUE(fs::is_symlink(report));
  EXPECT_EQ(snapshot(mine), before);
  EXPECT_FALSE(fs::exists(dir_ / "R.previous"));
}

// The report's folder has the mode of any folder the user makes (0777 less the umask): mkdtemp's 0700 staging folder
// made every report unreadable to the user's group and others (a report served by a web server, a CI artifact).
TEST_F(OutputSafetyTest, TheReportFolderHasTheModeOfAnyFolderTheUserMakes) {
  const mode_t old = ::umask(027);
  const ProgramResult r = writeShard(dir_ / "S");
  ::umask(old);
  ASSERT_EQ(r.exit_status, 0) << r.err;
  struct stat st {};
  ASSERT_EQ(::stat((dir_ / "S").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0750u);
}

}  // namespace
}  // namespace crankcheck
