// `aperture bench soak` end to end on a short flight (24 simulated s, a 376 x 240 LED camera):
// soak.csv has one row per sample with the documented columns, summary.json the figures, the
// bounded records and the acceptance; bad values are usage errors (exit 2).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

TEST(BenchSoakCommand, ShortSoakWritesSamplesFiguresAndBoundedRecords) {
  TempFolder out("bench_soak");
  const CommandResult run = RunAperture(
      "bench soak --duration 24 --interval 4 --set cameras.ground.width=376 "
      "--set cameras.ground.height=240 --out " +
      out.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::ifstream csv(out.path() + "/soak.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "t_s,wall_s,cpu_s,rss_mib,frames,frame_wall_median_ms,frame_wall_max_ms,"
            "frame_cpu_median_ms,frame_cpu_max_ms");
  EXPECT_EQ(CountLines(out.path() + "/soak.csv"), 1u + 6u);  // samples at 4, 8, ..., 24 s
  const nlohmann::json summary = ReadJson(out.path() + "/summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["command"], "bench soak");
  EXPECT_NEAR(summary["run"]["sim_time_s"].get<double>(), 24.0, 1e-6);
  EXPECT_GT(summary["run"]["cpu_time_s"].get<double>(), 0.0);
  const nlohmann::json& rss = summary["soak"]["rss_mib"];
  EXPECT_NEAR(rss["reference_t_s"].get<double>(), 12.0, 1e-6);  // min(60 s, duration / 2)
  EXPECT_NEAR(rss["end_t_s"].get<double>(), 24.0, 1e-6);
  EXPECT_GT(rss["reference"].get<double>(), 1.0);
  EXPECT_NEAR(rss["growth_percent"].get<double>(),
              100.0 * (rss["end"].get<double>() / rss["reference"].get<double>() - 1.0), 1e-9);
  const nlohmann::json& timing = summary["soak"]["frame_time_ms"];
  EXPECT_DOUBLE_EQ(timing["window_s"].get<double>(), 12.0);
  EXPECT_GT(timing["cpu_median_first_window"].get<double>(), 0.0);
  EXPECT_GT(timing["cpu_median_last_window"].get<double>(), 0.0);
  EXPECT_TRUE(timing["cpu_drift_percent"].is_number());
  EXPECT_TRUE(summary["acceptance"]["rss_growth_below_5_percent"].is_boolean());
  // The flight keeps its last 20 s of records, trimmed once two windows old: all of a 24 s flight
  // (200 Hz ground truth).
  EXPECT_EQ(summary["buffers"]["sitl_trajectory"]["size"], 24 * 200 + 1);
  EXPECT_EQ(summary["buffers"]["soak_samples"]["size"], 6);
  EXPECT_TRUE(summary["mission"]["passed"].is_boolean());
  EXPECT_TRUE(std::filesystem::exists(out.path() + "/report.html"));
}

TEST(BenchSoakCommand, BadValuesAreUsageErrors) {
  TempFolder out("bench_soak_usage");
  for (const std::string values :
       {"--duration 0", "--duration -5", "--duration nan", "--duration inf", "--interval 0",
        "--interval nan", "--duration 20 --interval 30"}) {
    const CommandResult run = RunAperture("bench soak " + values + " --out " + out.path());
    EXPECT_EQ(run.exit_code, 2) << values << "\n" << run.output;
    EXPECT_FALSE(std::filesystem::exists(out.path() + "/soak.csv")) << values;
  }
  const CommandResult interval =
      RunAperture("bench soak --duration 20 --interval 30 --out " + out.path());
  EXPECT_NE(interval.output.find("longer than --duration"), std::string::npos) << interval.output;
  const CommandResult listed = RunAperture("bench");
  EXPECT_NE(listed.output.find("aperture bench soak"), std::string::npos) << listed.output;
}

}  // namespace
}  // namespace aperture::apps::testing
