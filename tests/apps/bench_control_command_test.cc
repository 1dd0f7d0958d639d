// `aperture bench control --quick` end to end: the summary keys of the drag section, the report.
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
  const CommandResult result = RunAperture(
      "bench control --quick --only drag,mixer --seed 2 --set vehicle.mismatch=false --out " +
      out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["inputs"]["seed"], 2);
  EXPECT_EQ(summary["inputs"]["sections"], nlohmann::json::array({"drag", "mixer"}));
  EXPECT_TRUE(summary["timing"].contains("drag_s"));
  EXPECT_TRUE(summary["timing"].contains("mixer_s"));
  EXPECT_EQ(summary["cost"]["trials"], 2);  // a trial is a section
  // Drag compensation (F.6-F.30) cuts the average tracking error (F.39) on both trajectories:
  // the simulated vehicle has rotor drag, so flying without it leaves a drag-sized error.
  for (const char* trajectory : {"circle", "lemniscate"}) {
    const double off = summary["drag"][trajectory]["E_a_off"].get<double>();
    const double on = summary["drag"][trajectory]["E_a_on"].get<double>();
    EXPECT_GT(on, 0.0) << trajectory;
    EXPECT_LT(on, 0.5 * off) << trajectory;
  }
  // The identification on the circle (Nelder-Mead from d = 0) lands within 10 % of the vehicle's
  // true drag.
  const nlohmann::json& identified = summary["drag"]["identified"];
  for (const char* key : {"dx", "dy"}) {
    const double truth = identified["true"][key].get<double>();
    EXPECT_GT(truth, 0.0) << key;
    EXPECT_NEAR(identified["circle"][key].get<double>(), truth, 0.1 * truth) << key;
  }
  // Table F.1's six rows (and the nominal model's) in the summary, beside the thesis' values.
  EXPECT_EQ(summary["drag"]["table_f1"].size(), 8u);
  EXPECT_TRUE(fs::exists(out / "report.html"));
}

// The vehicle comes from the configuration: the identification finds the drag set with --set,
// and summary.json carries the full effective vehicle and control stack.
TEST(BenchControlCommand, ConfiguredVehicleIsTheOneTheSectionsFly) {
  TempFolder temp("bench_control_config");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture(
      "bench control --quick --only drag --set 'dynamics.vehicle.rotor_drag_D_per_s=[0.3, "
      "0.2, 0]' --set control.mixer=one_shot --set vehicle.mismatch=false --out " +
      out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  const nlohmann::json& identified = summary["drag"]["identified"];
  EXPECT_DOUBLE_EQ(identified["true"]["dx"].get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(identified["true"]["dy"].get<double>(), 0.2);
  EXPECT_NEAR(identified["circle"]["dx"].get<double>(), 0.3, 0.03);
  EXPECT_NEAR(identified["circle"]["dy"].get<double>(), 0.2, 0.02);
  const nlohmann::json& config = summary["config"];
  EXPECT_EQ(config["control"]["mixer"], "one_shot");
  EXPECT_EQ(config["dynamics"]["vehicle"]["rotor_drag_D_per_s"],
            nlohmann::json::array({0.3, 0.2, 0}));
  EXPECT_EQ(config["control"]["position"]["p_xy_per_s2"], 5);  // defaults are written too
  EXPECT_TRUE(config.contains("imu"));
  EXPECT_TRUE(config.contains("range"));
  EXPECT_EQ(config["vehicle"]["mismatch"], false);
  EXPECT_TRUE(config["vehicle"].contains("mismatch_bounds"));

  const CommandResult typo = RunAperture("bench control --only drag --set control.mixr=x --out " +
                                         (fs::path(temp.path()) / "typo").string());
  EXPECT_NE(typo.exit_code, 0);
  // Named by its source, the --set item (the bench rebuilds from JSON, but the command reads
  // the options first).
  EXPECT_NE(typo.output.find("--set control.mixr=x"), std::string::npos) << typo.output;
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
