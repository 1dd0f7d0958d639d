// `aperture bench gapflyt --quick` end to end (the smoke run of the Table III analog): one
// closed-loop flight through the ellipse opening (trial 0) with the moment servo, its figures scored on
// ground truth in summary.json, trials.csv and report.html; bad options named.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

TEST(BenchGapflytCommand, QuickRunFliesThroughTheTrueOpening) {
  TempFolder temp("bench_gapflyt");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result =
      RunAperture("bench gapflyt --quick --laws moments --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  const nlohmann::json& moments = summary["laws"]["moments"];
  EXPECT_EQ(moments["trials"], 1);
  ASSERT_EQ(summary["per_trial"].size(), 1u);
  const nlohmann::json& trial = summary["per_trial"][0];
  EXPECT_EQ(trial["shape"], "ellipse");  // trial 0
  const nlohmann::json& f = trial["figures"];
  // Against ground truth: crossed the wall plane inside the true opening without a collision,
  // every part of the footprint clear of its edge, from a detection overlapping the true opening
  // (projected with the true pose of its reference frame) by >= 75 %.
  EXPECT_TRUE(trial["passed"].get<bool>()) << f.dump(1);
  EXPECT_TRUE(f["inside_opening"].get<bool>());
  EXPECT_GT(f["clearance_m"].get<double>(), 0.0);
  EXPECT_GE(f["detection"]["overlap"].get<double>(), 0.75);
  EXPECT_DOUBLE_EQ(moments["success_rate"].get<double>(), 1.0);
  EXPECT_EQ(CountLines(out / "trials.csv"), 2u);
  EXPECT_TRUE(fs::exists(out / "report.html"));
}

TEST(BenchGapflytCommand, RejectsAnUnknownLawAndSceneOverrides) {
  TempFolder temp("bench_gapflyt_bad");
  const fs::path out = fs::path(temp.path()) / "out";
  CommandResult result = RunAperture("bench gapflyt --quick --laws magic --out " + out.string());
  EXPECT_EQ(result.exit_code, 2);  // a usage mistake, the known laws listed
  EXPECT_NE(result.output.find("'magic' is not one of: moments, pid"), std::string::npos)
      << result.output;
  result = RunAperture("bench gapflyt --quick --set gapflyt.shape=star --out " + out.string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("gapflyt.shape=star"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace aperture::apps::testing
