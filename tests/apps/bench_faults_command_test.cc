// `aperture bench faults` end to end on short LED-hover flights: one fault at its default level
// and twice it beside the baseline; summary.json counts every flight once by level, flights.csv
// has a row per flight; bad values are usage errors (exit 2).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

TEST(BenchFaultsCommand, OutageAtTwoLevelsBesideTheBaseline) {
  TempFolder out("bench_faults");
  const CommandResult run = RunAperture(
      "bench faults --mission led --trials 2 --duration 3 --faults perception_outage "
      "--levels acceptance --set cameras.ground.width=376 --set cameras.ground.height=240 "
      "--out " +
      out.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json summary = ReadJson(out.path() + "/summary.json");
  EXPECT_EQ(summary["command"], "bench faults");
  EXPECT_EQ(summary["baseline"]["trials"], 2);
  const nlohmann::json& levels = summary["faults"]["perception_outage"]["levels"];
  ASSERT_EQ(levels.size(), 3u);  // none (the baseline), default 0.25 s, twice 0.5 s
  EXPECT_DOUBLE_EQ(levels[0]["level"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(levels[1]["level"].get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(levels[2]["level"].get<double>(), 0.5);
  for (const nlohmann::json& level : levels) {
    EXPECT_EQ(level["trials"], 2);
    EXPECT_EQ(
        level["success"].get<int>() + level["safe_abort"].get<int>() + level["crash"].get<int>(),
        2);
  }
  EXPECT_EQ(summary["faults"].size(), 1u);
  EXPECT_EQ(summary["acceptance"].size(), 2u);
  EXPECT_EQ(CountLines(out.path() + "/flights.csv"), 1u + 6u);
  EXPECT_TRUE(std::filesystem::exists(out.path() + "/report.html"));
}

TEST(BenchFaultsCommand, BadValuesAreUsageErrors) {
  TempFolder out("bench_faults_usage");
  for (const std::string values :
       {"--mission nowhere", "--mission led --faults wind", "--mission led --levels all",
        "--mission led --trials 0", "--mission led --duration nan", "--faults gust"}) {
    const CommandResult run = RunAperture("bench faults " + values + " --out " + out.path());
    EXPECT_EQ(run.exit_code, 2) << values << "\n" << run.output;
    EXPECT_FALSE(std::filesystem::exists(out.path() + "/flights.csv")) << values;
  }
  const CommandResult listed =
      RunAperture("bench faults --mission led --faults wind --out " + out.path());
  EXPECT_NE(listed.output.find("perception_outage"), std::string::npos) << listed.output;
}

}  // namespace
}  // namespace aperture::apps::testing
