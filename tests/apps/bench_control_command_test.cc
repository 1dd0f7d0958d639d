// `aperture bench control --quick` end to end: the summary keys of the drag sections, the report.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

TEST(BenchControlCommand, QuickRunWritesTheDragKeysAndReport) {
  TempFolder temp("bench_control");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result =
      RunAperture("bench control --quick --only drag,drag_id --seed 2 --out " + out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("[2/2] drag_id"), std::string::npos) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["inputs"]["seed"], 2);
  for (const char* trajectory : {"circle", "lemniscate"}) {
    for (const char* key : {"E_a_off", "E_a_on"}) {
      EXPECT_GT(summary["drag"][trajectory][key].get<double>(), 0.0) << trajectory << "." << key;
    }
  }
  for (const char* group : {"true", "estimated"}) {
    for (const char* key : {"dx", "dy"}) {
      EXPECT_GT(summary["drag_id"][group][key].get<double>(), 0.0) << group << "." << key;
    }
  }
  EXPECT_TRUE(fs::exists(out / "report.html"));
}

TEST(BenchControlCommand, UnknownSectionIsNamed) {
  TempFolder temp("bench_control_bad");
  const CommandResult result =
      RunAperture("bench control --only drag,wind --out " + temp.path() + "/out");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("unknown section 'wind'"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace aperture::apps::testing
