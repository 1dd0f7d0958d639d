// `aperture bench faults` end to end on short LED-hover flights: one fault at its default level
// and twice it beside the baseline; summary.json counts every flight once by level, flights.csv
// has a row per flight; bad values are usage errors (exit 2).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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

  // The last flight (repeat 1, the 0.5 s outage) flown again by `aperture sim` from its replay
  // column is the same flight: the same mission verdict, to the printed digits.
  std::ifstream flights(out.path() + "/flights.csv");
  std::string line, last;
  while (std::getline(flights, line)) last = line;
  const std::size_t replay_at = last.find("aperture sim led ");
  ASSERT_NE(replay_at, std::string::npos) << last;
  std::string replay = last.substr(replay_at + std::string("aperture ").size());
  if (!replay.empty() && replay.back() == '"') replay.pop_back();
  EXPECT_NE(replay.find("--fault perception_outage=0.5 --fault-seed "), std::string::npos);
  TempFolder again("bench_faults_replay");
  const CommandResult sim = RunAperture(replay + " --video-every 1000 --out " + again.path());
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  const nlohmann::json replayed = ReadJson(again.path() + "/summary.json");
  EXPECT_EQ(replayed["inputs"]["fault"]["name"], "perception_outage");
  // "LED hover: held, RMS error 0.012 m (0.012 m outside pushes)" (the frame counts that follow
  // differ: the bench does not render the frames the mission ignores).
  const std::size_t verdict_at = sim.output.rfind("LED hover: ");
  ASSERT_NE(verdict_at, std::string::npos) << sim.output;
  const std::string verdict =
      sim.output.substr(verdict_at, sim.output.find("pushes)", verdict_at) - verdict_at);
  EXPECT_NE(last.find(verdict), std::string::npos) << verdict << " vs " << last;
}

// A flight of the gap fault sweep that passed the gap with a 0.3 m/s^2 accelerometer bias and
// then drifted away at 0.56 m/s on the IMU alone: the recovery's visual odometry (the downward
// camera of Sec. II-F, emulated) brings it to a hover; with the odometry's start put beyond the
// flight it drifts again.
TEST(BenchFaultsCommand, GapFlightWithAnAccelerometerBiasRecoversOnTheOdometry) {
  const std::string flight =
      "sim gap --seed 5235680414843546157 --duration 15 --fault accel_bias=0.3 --fault-seed "
      "11198296037271458925 --set gap.roll_deg=36.725 --set gap.pitch_deg=24.433 --video-every "
      "1000 ";
  TempFolder out("sim_gap_bias");
  const CommandResult run = RunAperture(flight + "--out " + out.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json mission = ReadJson(out.path() + "/summary.json")["mission"];
  EXPECT_TRUE(mission["passed"].get<bool>()) << mission.dump(2);
  EXPECT_GT(mission["recovery_odometry_fused"].get<int>(), 0);

  TempFolder imu_only("sim_gap_bias_imu_only");
  const CommandResult drift = RunAperture(
      flight + "--set mission.recovery_odometry_delay_s=1e9 --out " + imu_only.path());
  ASSERT_EQ(drift.exit_code, 0) << drift.output;
  const nlohmann::json drifted = ReadJson(imu_only.path() + "/summary.json")["mission"];
  EXPECT_FALSE(drifted["passed"].get<bool>());
  EXPECT_NE(drifted["failure_reason"].get<std::string>().find("not hovering"), std::string::npos)
      << drifted.dump(2);
  EXPECT_EQ(drifted["recovery_odometry_fused"].get<int>(), 0);
}

TEST(BenchFaultsCommand, SimRejectsABadFault) {
  TempFolder out("sim_bad_fault");
  for (const std::string fault : {"wind=1", "motor_loss=0.5", "motor_loss", "gust=nan"}) {
    const CommandResult run =
        RunAperture("sim led --duration 0.5 --fault " + fault + " --out " + out.path());
    EXPECT_EQ(run.exit_code, 2) << fault << ": " << run.output;
    EXPECT_NE(run.output.find("fault"), std::string::npos) << run.output;
  }
  const CommandResult unknown =
      RunAperture("sim led --duration 0.5 --fault wind=1 --out " + out.path());
  EXPECT_NE(unknown.output.find("motor_loss"), std::string::npos) << unknown.output;  // the known
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
