#pragma once
// A fresh directory under the system temp folder, removed with its contents on destruction.
// Named after the running test and the process id so parallel ctest runs do not collide.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace aperture::test_support {

class TempDirectory {
 public:
  TempDirectory() {
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "aperture_" + std::string(test->test_suite_name()) + "_" + test->name() +
                       "_" + std::to_string(::getpid());
    for (char& c : name) {
      if (c == '/') c = '_';  // parameterized test names contain '/'
    }
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDirectory(const TempDirectory&) = delete;
  TempDirectory& operator=(const TempDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace aperture::test_support
