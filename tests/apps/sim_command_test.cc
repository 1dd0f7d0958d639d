// `aperture sim` end to end on built-in scenarios with tiny cameras: outputs, outcome, crashes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

TEST(SimCommand, HoverInTheGapScenarioWritesEveryOutput) {
  TempFolder temp("sim");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture(
      "sim gap --duration 0.5 --seed 3 --set cameras.front.width=94 --set cameras.front.height=60 "
      "--out " +
      out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["outcome"], "duration_reached");
  EXPECT_EQ(summary["inputs"]["seed"], 3);
  EXPECT_NEAR(summary["sim_time_s"].get<double>(), 0.5, 1e-6);
  EXPECT_GT(summary["real_time_factor"].get<double>(), 0.0);
  // `gap` flies the gap mission; 94x60 frames are too coarse for the detector, so it holds the
  // hover it started in (hover thrust, zero rates) without disturbances: sub-centimetre.
  EXPECT_EQ(summary["inputs"]["autopilot"], "gap_mission");
  EXPECT_EQ(summary["mission"]["phase"], "detect");
  EXPECT_EQ(summary["mission"]["passed"], false);
  EXPECT_LT(summary["hover_error_m"]["max"].get<double>(), 0.01);
  // 50 Hz camera over [0, 0.5] s inclusive.
  EXPECT_EQ(summary["cameras"][0]["frames_delivered"], 26);
  // 200 Hz ground truth over 0.5 s plus the start; TUM has one comment line, the CSV a header.
  EXPECT_EQ(CountLines(out / "trajectory.tum"), 1u + 101u);
  EXPECT_EQ(CountLines(out / "trajectory.csv"), 1u + 101u);
  EXPECT_EQ(CountLines(out / "commands.csv"), 1u + 51u);  // 100 Hz autopilot
  EXPECT_TRUE(fs::exists(out / "report.html"));
  ASSERT_TRUE(summary["outputs"].contains("video"));
  EXPECT_GT(fs::file_size(out / summary["outputs"]["video"].get<std::string>()), 0u);
}

TEST(SimCommand, VideoAndThirdPersonViewTakeEveryNthFrameAndKeyFrames) {
  TempFolder temp("sim_chase");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture(
      "sim gapflyt --duration 1 --set cameras.front.width=80 --set cameras.front.height=60 "
      "--set cameras.front.rate_hz=30 --video-every 2 --chase-every 3 --chase-height 30 --out " +
      out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  // 30 Hz over [0, 1] s: camera frames 0..30; every 2nd: 16 video frames 0..15 at 15 Hz. Chase
  // every 3rd: 0, 3, ..., 15 (6); key frames every ceil((30 / 2) / 8) = 2nd video frame:
  // 0, 2, ..., 14 (8), rendered afresh too; both: 0, 6, 12.
  EXPECT_EQ(summary["cameras"][0]["frames_delivered"], 31);
  EXPECT_EQ(summary["video"]["frames"], 16);
  EXPECT_DOUBLE_EQ(summary["video"]["rate_hz"].get<double>(), 15.0);
  EXPECT_EQ(summary["video"]["chase_renders"], 6 + 8 - 3);
  const nlohmann::json& timing = summary["timing"];
  EXPECT_GT(timing["chase_render_s"].get<double>(), 0.0);
  EXPECT_GE(timing["hooks_s"].get<double>(), timing["chase_render_s"].get<double>());
  std::ifstream report(out / "report.html");
  const std::string html((std::istreambuf_iterator<char>(report)), {});
  int jpeg_images = 0;
  for (size_t at = html.find("data:image/jpeg;base64,"); at != std::string::npos;
       at = html.find("data:image/jpeg;base64,", at + 1)) {
    ++jpeg_images;
  }
  EXPECT_EQ(jpeg_images, 8);

  const CommandResult bad = RunAperture("sim gapflyt --duration 0.1 --chase-every 0 --out " +
                                        (fs::path(temp.path()) / "bad").string());
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--chase-every"), std::string::npos) << bad.output;
}

std::string ReadFile(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(file)), {});
}

TEST(SimCommand, SameSeedGivesAnIdenticalTrajectoryAndAnotherSeedADifferentOne) {
  TempFolder temp("sim_seed");
  // `led`: the seed drives the gusts and the IMU and camera noise the LED hover flies through
  // (from 0.5 s, when it starts closing the loop on the LED poses; 188 x 120 still tracks them).
  const auto trajectory_csv = [&](const std::string& name, int seed) {
    const fs::path out = fs::path(temp.path()) / name;
    const CommandResult result = RunAperture(
        "sim led --duration 0.8 --seed " + std::to_string(seed) +
        " --set cameras.ground.width=188 --set cameras.ground.height=120 --out " + out.string());
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return ReadFile(out / "trajectory.csv");
  };
  const std::string first = trajectory_csv("first", 5);
  EXPECT_EQ(std::count(first.begin(), first.end(), '\n'), 1 + 161);  // header + 200 Hz, 0.8 s
  EXPECT_EQ(trajectory_csv("again", 5), first);
  EXPECT_NE(trajectory_csv("other", 6), first);
}

TEST(SimCommand, UnknownMissionKeyIsRejectedByName) {
  TempFolder temp("sim_mission_key");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture(
      "sim gap --duration 0.1 --set cameras.front.width=94 --set cameras.front.height=60 "
      "--set mission.hover_sec=1 --out " +
      out.string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("mission.hover_sec"), std::string::npos) << result.output;
}

TEST(SimCommand, StartingInTheGroundEndsWithAGroundCollision) {
  TempFolder temp("sim_crash");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture(
      "sim gapflyt --duration 2 --set cameras.front.width=80 --set cameras.front.height=60 "
      "--set 'vehicle.start.p_m=[0, 0, 0.05]' --out " +
      out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["outcome"], "collision");
  EXPECT_EQ(summary["collision"]["object"], "ground");
  EXPECT_DOUBLE_EQ(summary["collision"]["contact_p_W_m"][2].get<double>(), 0.0);
  EXPECT_LT(summary["sim_time_s"].get<double>(), 0.01);
}

TEST(SimCommand, UnknownScenarioFailsNamingIt) {
  TempFolder temp("sim_bad");
  const CommandResult result =
      RunAperture("sim nowhere --out " + (fs::path(temp.path()) / "out").string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("nowhere"), std::string::npos) << result.output;
}

// Issue 12 acceptance: summary.json holds the full effective configuration (scenario, SITL blocks,
// every mission parameter including the controller and recovery gains), and `--config` with that
// file alone (no --seed, no --set) flies the same gap mission again, byte for byte.
TEST(SimCommand, SummaryConfigurationReproducesTheGapFlightByteForByte) {
  TempFolder temp("sim_reproduce");
  const auto run = [&](const std::string& name, const std::string& arguments) {
    const fs::path out = fs::path(temp.path()) / name;
    const CommandResult result = RunAperture("sim gap --duration 1.2 --video-every 100 " +
                                             arguments + " --out " + out.string());
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return out;
  };
  const fs::path first =
      run("first",
          "--seed 4 --set gap.roll_deg=20 --set mission.hover_s=0.3 "
          "--set mission.controller.p_xy_per_s2=6 --set imu.accel_noise_density=0.01");
  const nlohmann::json config = ReadJson(first / "summary.json")["config"];
  EXPECT_EQ(config["seed"], 4);
  EXPECT_EQ(config["mission"]["name"], "gap");
  EXPECT_EQ(config["gap"]["roll_deg"], 20);
  EXPECT_EQ(config["mission"]["hover_s"], 0.3);
  EXPECT_EQ(config["mission"]["controller"]["p_xy_per_s2"], 6);
  // Values nobody set are written too: defaults and what the scenario derives.
  EXPECT_EQ(config["mission"]["recovery"]["controller"]["p_z_per_s2"], 15);
  EXPECT_EQ(config["mission"]["filter"]["accel_noise_density"], 0.01);  // from the IMU block
  EXPECT_EQ(config["mission"]["detector"]["opening_size_m"], nlohmann::json::array({0.8, 0.28}));
  EXPECT_EQ(config["range"]["max_range_m"], 14);

  const std::string summary = (first / "summary.json").string();
  const fs::path again = run("again", "--config " + summary);
  EXPECT_EQ(ReadJson(again / "summary.json")["config"], config);
  const std::string trajectory = ReadFile(first / "trajectory.csv");
  EXPECT_EQ(std::count(trajectory.begin(), trajectory.end(), '\n'), 1 + 241);  // 200 Hz, 1.2 s
  EXPECT_EQ(ReadFile(again / "trajectory.csv"), trajectory);
  // The comparison sees a change: the same configuration with another seed flies differently.
  const fs::path reseeded = run("reseeded", "--config " + summary + " --seed 5");
  EXPECT_NE(ReadFile(reseeded / "trajectory.csv"), trajectory);
}

// The mission a run flew is part of its configuration: --mission is recorded as mission.name, so
// the summary flies the same (non-default) mission again.
TEST(SimCommand, SummaryConfigurationKeepsTheMissionChosenOnTheCommandLine) {
  TempFolder temp("sim_mission_name");
  const auto run = [&](const std::string& name, const std::string& arguments) {
    const fs::path out = fs::path(temp.path()) / name;
    const CommandResult result = RunAperture(
        "sim gap --duration 0.3 --video-every 100 --set cameras.front.width=94 "
        "--set cameras.front.height=60 " +
        arguments + " --out " + out.string());
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return ReadJson(out / "summary.json");
  };
  const nlohmann::json first = run("first", "--mission hover");
  EXPECT_EQ(first["mission"]["name"], "hover");
  EXPECT_EQ(first["config"]["mission"]["name"], "hover");
  const std::string summary = (fs::path(temp.path()) / "first" / "summary.json").string();
  EXPECT_EQ(run("again", "--config " + summary)["mission"]["name"], "hover");
  EXPECT_EQ(run("default", "")["mission"]["name"], "gap");
  // Issue 15's spelling: --set mission=NAME is mission.name.
  EXPECT_EQ(run("shorthand", "--set mission=hover")["mission"]["name"], "hover");
}

}  // namespace
}  // namespace aperture::apps::testing
