#pragma once
/// @file
/// A folder made fresh for one test (mkdtemp under the system's temporary folder), removed with everything in it when
/// the test ends: only what the test and the program under test wrote. Shared by the CLI tests (run_cli.h) and the
/// unit tests that write files.

#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace crankcheck::testing {

/// A folder made fresh for one test (mkdtemp under the system's temporary folder, so it never existed before) and
/// removed with everything in it when the test ends: only what the test and the program under test wrote.
class FreshFolder {
 public:
  FreshFolder() {
    std::string name = (std::filesystem::temp_directory_path() / "crankcheck_test_XXXXXX").string();
    if (::mkdtemp(name.data()) == nullptr) throw std::runtime_error("mkdtemp failed under " + name);
    path_ = name;
  }
  ~FreshFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  FreshFolder(const FreshFolder&) = delete;
  FreshFolder& operator=(const FreshFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace crankcheck::testing
