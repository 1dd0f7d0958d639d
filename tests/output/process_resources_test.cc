#include "output/process_resources.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "tests/support/message_of.h"
#include "tests/support/temp_directory_test.h"

namespace aperture::output {
namespace {

using ProcessResourcesTest = aperture::testing::TempDirectoryTest;

TEST(ProcessResources, ResidentSetOfThisProcessIsPlausibleAndSeesAnAllocation) {
  const double before = ResidentSetBytes();
  // A test binary with its libraries is resident in more than 1 MiB and far less than 64 GiB.
  EXPECT_GT(before, 1024.0 * 1024.0);
  EXPECT_LT(before, 64.0 * 1024 * 1024 * 1024);
  // 64 MiB written (so resident) shows up.
  std::vector<char> block(64 << 20, 1);
  const double after = ResidentSetBytes();
  EXPECT_GT(after - before, 48.0 * 1024 * 1024) << static_cast<int>(block.back());
}

TEST_F(ProcessResourcesTest, ReadsVmRssInKibibytes) {
  const std::string path = WriteFile(
      "status", "Name:\taperture\nVmPeak:\t  999999 kB\nVmRSS:\t    2048 kB\nThreads: 1\n");
  EXPECT_DOUBLE_EQ(ResidentSetBytes(path), 2048.0 * 1024.0);
}

TEST_F(ProcessResourcesTest, MissingFileOrLineIsAClearError) {
  const std::string missing = (directory_ / "none").string();
  EXPECT_NE(
      test_support::MessageOf<std::runtime_error>([&] { ResidentSetBytes(missing); }).find(missing),
      std::string::npos);
  const std::string no_line = WriteFile("status", "Name:\taperture\n");
  EXPECT_NE(test_support::MessageOf<std::runtime_error>([&] {
              ResidentSetBytes(no_line);
            }).find("no VmRSS"),
            std::string::npos);
  const std::string bad = WriteFile("bad", "VmRSS:\tmany\n");
  EXPECT_NE(test_support::MessageOf<std::runtime_error>([&] {
              ResidentSetBytes(bad);
            }).find("unreadable VmRSS"),
            std::string::npos);
}

TEST(ProcessResources, ThreadCpuTimeAdvancesWithWork) {
  const double start = ThreadCpuSeconds();
  volatile double sink = 0.0;
  for (int i = 0; i < 20000000; ++i) sink = sink + 1e-9 * i;
  EXPECT_GT(ThreadCpuSeconds(), start);
}

}  // namespace
}  // namespace aperture::output
