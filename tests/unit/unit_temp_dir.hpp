#pragma once
// A folder of one unit test's own under the temporary folder, named by the process and the test:
// empty at construction, removed with everything in it at destruction. Two runs of the suite at
// once do not share it, and nothing is left behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace maptr::testing {

class UnitTempDir {
 public:
  explicit UnitTempDir(const std::string& name)
      : path_((std::filesystem::path(::testing::TempDir()) /
               ("maptr-unit-" + std::to_string(::getpid()) + "-" + name))
                  .string()) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~UnitTempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  UnitTempDir(const UnitTempDir&) = delete;
  UnitTempDir& operator=(const UnitTempDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace maptr::testing
