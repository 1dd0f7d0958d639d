// `make demo` end to end: scripts/demo.sh with the built binary (the 14 s gap flight through the
// gap rolled by 30 deg, ~5-15 s wall) passes the gap and writes the video and the report it
// points the user to. Labelled `demo` in ctest (`ctest -LE demo` skips it).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

TEST(Demo, GapFlightPassesAndWritesTheVideoAndReportItNames) {
  TempFolder temp("demo");
  const fs::path out = fs::path(temp.path()) / "demo";
  const CommandResult result = RunShellCommand(std::string(APERTURE_DEMO_SCRIPT) + " " +
                                               APERTURE_BINARY + " " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["inputs"]["autopilot"], "gap_mission");
  ASSERT_TRUE(summary.contains("mission")) << summary.dump(2);
  EXPECT_EQ(summary["mission"]["passed"], true) << summary["mission"].dump(2);
  EXPECT_TRUE(fs::exists(out / "report.html"));
  ASSERT_TRUE(summary["outputs"].contains("video"));
  const fs::path video = out / summary["outputs"]["video"].get<std::string>();
  ASSERT_TRUE(fs::exists(video)) << video;
  EXPECT_GT(fs::file_size(video), 0u);
  // The script's last line names the file written (.mp4, or .avi where the writer fell back).
  EXPECT_NE(result.output.find("(video: " + video.string() + ")"), std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace aperture::apps::testing
