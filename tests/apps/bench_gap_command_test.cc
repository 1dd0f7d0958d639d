// `aperture bench gap` end to end: the figures of summary.json, trials.csv, report.html, the
// detector section, bad flags.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

TEST(BenchGapCommand, TwoGroundTruthTrialsWriteTheTableIKeys) {
  TempFolder temp("bench_gap");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture(
      "bench gap --trials 2 --seed 4 --autopilot ground_truth --duration 6 "
      "--vehicle-mismatch off --out " +
      out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["trials"], 2);
  EXPECT_EQ(summary["inputs"]["seed"], 4);
  EXPECT_EQ(summary["inputs"]["vehicle_mismatch"], false);
  // The ground-truth autopilot has no lead-in: the paper's configuration is not flown again.
  EXPECT_EQ(summary["inputs"]["paper_configuration"], false);
  EXPECT_FALSE(summary["table_i"].contains("paper"));
  EXPECT_EQ(summary["table_i"]["ours"]["trials_with_plan"], 2);
  // Ground truth on the vehicle = model flies the planned traverse: both pass.
  EXPECT_EQ(summary["successes"], 2);
  EXPECT_DOUBLE_EQ(summary["success_rate"].get<double>(), 1.0);
  const nlohmann::json& error = summary["error_at_gap"];
  for (const char* key : {"position_mean", "position_std", "velocity_mean", "velocity_std"}) {
    EXPECT_EQ(error[key].size(), 3u) << key;
  }
  EXPECT_EQ(error["orientation_mean_deg"].size(), 2u);
  EXPECT_EQ(error["orientation_std_deg"].size(), 2u);
  ASSERT_EQ(summary["per_trial"].size(), 2u);
  for (const nlohmann::json& trial : summary["per_trial"]) {
    EXPECT_GE(trial["roll_deg"].get<double>(), 0.0);
    EXPECT_LE(trial["roll_deg"].get<double>(), 45.0);
    EXPECT_GE(trial["pitch_deg"].get<double>(), 0.0);
    EXPECT_LE(trial["pitch_deg"].get<double>(), 30.0);
    EXPECT_TRUE(trial.contains("outcome"));
    EXPECT_TRUE(trial.contains("failure_reason"));
    // On ground truth the traverse is flown as planned: each axis within 5 cm at the gap
    // (README: 3 / 2 / 12 mm mean over 100 trials).
    ASSERT_EQ(trial["error_at_gap"]["position_m"].size(), 3u);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_LT(std::abs(trial["error_at_gap"]["position_m"][axis].get<double>()), 0.05);
    }
  }
  EXPECT_EQ(CountLines(out / "trials.csv"), 1u + 2u);
  EXPECT_TRUE(fs::exists(out / "report.html"));
  EXPECT_FALSE(summary.contains("detector"));
  EXPECT_FALSE(fs::exists(out / "detector_frames.csv"));
}

// --detector-sequences: rendered sequences after the flight, scored frame by frame, in
// summary.json "detector", detector_frames.csv and the report.
TEST(BenchGapCommand, DetectorSequencesWriteTheDetectorSection) {
  TempFolder temp("bench_gap_detector");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture(
      "bench gap --trials 1 --seed 4 --autopilot ground_truth --duration 1 "
      "--detector-sequences 2 --out " +
      out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  ASSERT_TRUE(summary.contains("detector")) << summary.dump();
  const nlohmann::json& d = summary["detector"];
  EXPECT_EQ(d["sequences"], 2);
  EXPECT_EQ(d["failed_sequences"], 0);
  EXPECT_GT(d["frames_in_view"].get<int>(), 10);
  EXPECT_LE(d["frames_in_view"].get<int>(), d["frames"].get<int>());
  // The detector finds the pattern in nearly every frame that shows it (bench: >= 99 %).
  EXPECT_GE(d["detection_rate"].get<double>(), 0.9);
  EXPECT_LT(d["rotation_error_median_deg"].get<double>(), 1.0);
  EXPECT_EQ(d["by_distance"].size(), 3u);
  EXPECT_EQ(summary["inputs"]["detector_sequences"], 2);
  EXPECT_EQ(CountLines(out / "detector_frames.csv"), 1u + d["frames"].get<std::size_t>());
  std::ifstream report(out / "report.html");
  const std::string html((std::istreambuf_iterator<char>(report)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("Detector on moving sequences"), std::string::npos);
  EXPECT_NE(result.output.find("detector:"), std::string::npos) << result.output;

  const CommandResult bad = RunAperture("bench gap --trials 1 --detector-sequences -1 --out " +
                                        (fs::path(temp.path()) / "bad").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--detector-sequences"), std::string::npos) << bad.output;

  const fs::path inverted = fs::path(temp.path()) / "inverted";
  const CommandResult steep =
      RunAperture("bench gap --trials 1 --min-roll-deg 50 --out " + inverted.string());
  EXPECT_EQ(steep.exit_code, 2) << steep.output;
  EXPECT_NE(steep.output.find("--min-roll-deg 50 is above --max-roll-deg 45"), std::string::npos)
      << steep.output;
  EXPECT_FALSE(fs::exists(inverted));  // refused before anything was written
}

// The default autopilot is the vision mission on rendered frames. Two seconds of unblurred 30 Hz
// frames keep this to seconds: no trial crosses and the errors are null, but every trial ran the
// camera + IMU path, and the detector found the gap in time to leave the detect phase (10
// detections) in every trial.
TEST(BenchGapCommand, MissionTrialsRunOnRenderedFrames) {
  TempFolder temp("bench_gap_mission");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture(
      "bench gap --trials 2 --duration 2 --motion-blur-subframes 1 "
      "--set cameras.front.supersampling=1 --set cameras.front.rate_hz=30 --out " +
      out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["inputs"]["autopilot"], "gap_mission");
  EXPECT_EQ(summary["inputs"]["vehicle_mismatch"], true);  // the default
  EXPECT_EQ(summary["trials"], 2);
  EXPECT_EQ(summary["successes"], 0);
  EXPECT_EQ(summary["error_at_gap"]["trials"], 0);
  // Every trial flown again with the paper's configuration; no plan in 2 s, counted as such.
  EXPECT_EQ(summary["table_i"]["paper"]["trials"], 2);
  EXPECT_EQ(summary["table_i"]["paper"]["trials_without_plan"], 2);
  EXPECT_EQ(CountLines(out / "paper_trials.csv"), 1u + 2u);
  for (const nlohmann::json& trial : summary["per_trial"]) {
    EXPECT_EQ(trial["outcome"], "duration_reached");
    EXPECT_EQ(trial["failure_reason"].get<std::string>().rfind("never crossed", 0), 0u);
    EXPECT_EQ(trial["autopilot_status"].get<std::string>().rfind("detect", 0), std::string::npos)
        << trial["autopilot_status"];
    // 30 Hz over [0, 2] s, less the seeded drops.
    EXPECT_EQ(trial["frames_delivered"].get<int>() + trial["frames_dropped"].get<int>() +
                  trial["frames_skipped"].get<int>(),
              61);
  }
  EXPECT_EQ(CountLines(out / "trials.csv"), 1u + 2u);
}

TEST(BenchGapCommand, RejectsAnInclinationRangeOutOfBounds) {
  TempFolder temp("bench_gap_bad");
  const CommandResult result =
      RunAperture("bench gap --max-roll-deg 95 --out " + (fs::path(temp.path()) / "out").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("--max-roll-deg"), std::string::npos) << result.output;
  for (const char* bad : {"--vehicle-mismatch maybe", "--vehicle big"}) {
    const CommandResult choice = RunAperture(std::string("bench gap ") + bad + " --out " +
                                             (fs::path(temp.path()) / "choice").string());
    EXPECT_EQ(choice.exit_code, 2) << bad << ": " << choice.output;
    EXPECT_NE(choice.output.find(std::string(bad).substr(0, std::string(bad).find(' '))),
              std::string::npos)
        << choice.output;
    EXPECT_FALSE(fs::exists(fs::path(temp.path()) / "choice" / "summary.json"));
  }
}

// Every mission parameter is settable in the bench (`mission` section) and reaches each trial's
// mission: a camera_id the scenario does not have fails every trial naming it, before a frame.
TEST(BenchGapCommand, MissionSectionReachesTheTrialsAndIsRecorded) {
  TempFolder temp("bench_gap_mission_config");
  const fs::path out = fs::path(temp.path()) / "out";
  const CommandResult result = RunAperture(
      "bench gap --trials 1 --duration 1 --set mission.camera_id=5 "
      "--set mission.recovery.max_vertical_speed_mps=0.4 --out " +
      out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json summary = ReadJson(out / "summary.json");
  EXPECT_EQ(summary["successes"], 0);
  EXPECT_NE(summary["per_trial"][0]["failure_reason"].get<std::string>().find("camera_id 5"),
            std::string::npos)
      << summary["per_trial"][0];
  const nlohmann::json& mission = summary["config"]["mission"];
  EXPECT_EQ(mission["camera_id"], 5);
  EXPECT_EQ(mission["recovery"]["max_vertical_speed_mps"], 0.4);
  EXPECT_EQ(mission["detector"]["outer_size_m"], nlohmann::json::array({1.3, 0.78}));

  const CommandResult typo = RunAperture("bench gap --trials 1 --set mission.hover_sec=1 --out " +
                                         (fs::path(temp.path()) / "typo").string());
  EXPECT_NE(typo.exit_code, 0);
  EXPECT_NE(typo.output.find("mission.hover_sec"), std::string::npos) << typo.output;
}

}  // namespace
}  // namespace aperture::apps::testing
