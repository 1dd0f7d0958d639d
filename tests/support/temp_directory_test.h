#pragma once
// A test fixture with a fresh folder per test (named after the test, removed afterwards) and a
// helper that writes a text file into it: for tests of loaders that read files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace aperture::testing {

class TempDirectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ =
        std::filesystem::temp_directory_path() /
        ("aperture_" +
         std::string(::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  // Writes `text` to `name` in the folder; returns its path.
  std::string WriteFile(const std::string& name, const std::string& text) const {
    const std::string path = (directory_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  std::filesystem::path directory_;
};

}  // namespace aperture::testing
