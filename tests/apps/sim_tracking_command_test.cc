// `aperture sim tracking` and `aperture sim recovery` end to end: summary keys, outputs, config
// errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

TEST(SimTrackingCommand, CircleWithAndWithoutDragCompensation) {
  TempFolder temp("sim_tracking");
  const fs::path on = fs::path(temp.path()) / "on";
  const fs::path off = fs::path(temp.path()) / "off";
  // 8 s: the 3 s ramp and most of two loops at 4 m/s.
  ASSERT_EQ(RunAperture("sim tracking --trajectory circle --duration 8 --out " + on.string())
                .exit_code,
            0);
  const CommandResult result = RunAperture(
      "sim tracking --trajectory circle --duration 8 --set control.drag_compensation=false "
      "--set control.body_rate=p_high --set control.mixer=one_shot --out " +
      off.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary_on = ReadJson(on / "summary.json");
  const nlohmann::json summary_off = ReadJson(off / "summary.json");
  EXPECT_EQ(summary_on["status"], "ok");
  EXPECT_EQ(summary_on["inputs"]["trajectory"], "circle");
  EXPECT_EQ(summary_on["control"]["body_rate"], "lqr");
  EXPECT_EQ(summary_off["control"]["body_rate"], "p_high");
  EXPECT_EQ(summary_off["control"]["mixer"], "one_shot");
  EXPECT_EQ(summary_off["control"]["drag_compensation"], false);
  EXPECT_NEAR(summary_on["sim_time_s"].get<double>(), 8.0, 1e-6);
  // Drag compensation with the exact model: millimetres; without it decimetres (Table F.1).
  EXPECT_LT(summary_on["tracking"]["E_a_m"].get<double>(), 0.02);
  EXPECT_GT(summary_off["tracking"]["E_a_m"].get<double>(), 0.05);
  EXPECT_EQ(summary_on["tracking"]["rmse_W_m"].size(), 3u);
  // 200 Hz ground truth over [0, 8] s plus a header.
  EXPECT_EQ(CountLines(on / "tracking.csv"), 1u + 1601u);
  for (const char* file : {"trajectory.csv", "commands.csv", "imu.csv", "report.html"}) {
    EXPECT_TRUE(fs::exists(on / file)) << file;
  }
}

TEST(SimTrackingCommand, BadControlValueNamesTheAllowedValues) {
  TempFolder temp("sim_tracking_bad");
  const CommandResult result = RunAperture(
      "sim tracking --set control.saturation=soft --out " + temp.path() + "/out");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("control.saturation"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("prioritized, clipping"), std::string::npos) << result.output;
}

TEST(SimRecoveryCommand, SeededThrowIsRecoveredThroughEveryStage) {
  TempFolder temp("sim_recovery");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture("sim recovery --seed 5 --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["recovery"]["outcome"], "recovered");
  const nlohmann::json& stages = summary["recovery"]["stage_times_s"];
  double previous = 0.0;
  for (const char* stage :
       {"attitude", "vertical_velocity", "height", "horizontal_velocity", "position"}) {
    ASSERT_TRUE(stages.contains(stage)) << stage;
    EXPECT_GE(stages[stage].get<double>(), previous) << stage;
    previous = stages[stage].get<double>();
  }
  EXPECT_EQ(CountLines(out / "stages.csv"), 1u + 5u);
  EXPECT_TRUE(fs::exists(out / "report.html"));
}

}  // namespace
}  // namespace aperture::apps::testing
