// `aperture bench led --quick` end to end: every summary key of issue 6 is written, the frames CSV
// has one row per tracked frame, and the quick figures meet the accuracy acceptance.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

TEST(BenchLedCommand, QuickRunWritesTheIssueKeys) {
  TempFolder out("bench_led");
  const CommandResult run = RunAperture("bench led --quick --seed 3 --out " + out.path());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json summary = ReadJson(out.path() + "/summary.json");
  EXPECT_EQ(summary["status"], "ok");
  const nlohmann::json& accuracy = summary["accuracy"];
  for (const char* key : {"position_error_mean", "position_error_std", "position_error_max",
                          "orientation_error_mean_deg", "orientation_error_std_deg",
                          "orientation_error_max_deg", "frames", "frames_with_pose"}) {
    EXPECT_TRUE(accuracy.contains(key)) << key;
  }
  for (const char* key : {"detection", "correspondence_brute_force", "prediction", "refinement"}) {
    ASSERT_TRUE(summary["timing"][key].is_number()) << key;
    EXPECT_GT(summary["timing"][key].get<double>(), 0.0) << key;
  }
  // Thesis Table C.1 is 0.74 cm / 0.79 deg; the issue asks for <= 0.5 cm / 0.5 deg mean, 2 cm max
  // on the 6-DOF excitation with four LEDs. The rendered sequence has sub-millimetre centroid
  // noise, so the quick run must meet them too.
  EXPECT_EQ(accuracy["leds"], 4);
  EXPECT_LE(accuracy["position_error_mean"].get<double>(), 0.005);
  EXPECT_LE(accuracy["position_error_max"].get<double>(), 0.02);
  EXPECT_LE(accuracy["orientation_error_mean_deg"].get<double>(), 0.5);
  EXPECT_EQ(accuracy["frames_with_pose_4_leds_visible"], accuracy["frames_with_4_leds_visible"]);
  // Sweep 0.3-5.6 m with five LEDs: every distance reported, close range tracked.
  const nlohmann::json& distances = summary["sweep"]["distances"];
  ASSERT_GE(distances.size(), 2u);
  EXPECT_DOUBLE_EQ(distances.front()["distance_m"].get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(distances.back()["distance_m"].get<double>(), 5.6);
  EXPECT_EQ(distances.front()["frames_with_pose"], distances.front()["frames"]);
  // Fig. C.7's outliers (> 90 deg, wrong labellings) per distance add up to the sweep's, and
  // (issue 21) none that the covariance is confident of passes verification.
  int outliers = 0;
  for (const nlohmann::json& distance : distances) {
    EXPECT_LE(distance["outliers_over_90deg"].get<int>(), distance["frames_with_pose"].get<int>());
    EXPECT_LE(distance["confident_wrong_labellings_verified"].get<int>(),
              distance["outliers_verified"].get<int>());
    EXPECT_DOUBLE_EQ(
        distance["outlier_fraction"].get<double>(),
        distance["outliers_over_90deg"].get<double>() / distance["frames"].get<double>());
    outliers += distance["outliers_over_90deg"].get<int>();
  }
  EXPECT_EQ(summary["sweep"]["outliers_over_90deg"], outliers);
  EXPECT_EQ(summary["sweep"]["confident_wrong_labellings_verified"], 0);
  EXPECT_TRUE(summary["acceptance"]["sweep_no_confident_wrong_labelling_verified"].get<bool>());
  // One LED of five occluded: the pose stays, without jumps; a fresh start finds it too.
  const nlohmann::json& occlusion = summary["occlusion"];
  EXPECT_GT(occlusion["frames_occluded"].get<int>(), 0);
  EXPECT_EQ(occlusion["frames_with_pose_occluded"], occlusion["frames_occluded"]);
  EXPECT_LE(occlusion["max_position_jump"].get<double>(), 0.02);
  EXPECT_TRUE(occlusion["fresh_start_pose"].get<bool>());
  // Merged LEDs: frames where they merge exist, and none gives a confident wrong pose.
  EXPECT_GT(summary["merged"]["frames_merged"].get<int>(), 0);
  EXPECT_EQ(summary["merged"]["confident_wrong_poses"], 0);
  // Table C.2's protocol: brute force in every frame, still a pose in (nearly) every frame;
  // mean <= max per step, the runs' frames all detected and labelled.
  for (const char* leds : {"n_L_4", "n_L_5"}) {
    const nlohmann::json& timing = summary["brute_force_timing"][leds];
    EXPECT_GE(timing["frames_with_pose"].get<double>(), 0.95 * timing["frames"].get<double>())
        << leds;
    EXPECT_EQ(timing["led_detection"]["samples"], timing["frames"]) << leds;
    EXPECT_EQ(timing["correspondence_search"]["samples"], timing["frames"]) << leds;
    for (const char* step :
         {"led_detection", "correspondence_search", "prediction", "pose_optimization"}) {
      EXPECT_GT(timing[step]["mean"].get<double>(), 0.0) << leds << " " << step;
      EXPECT_LE(timing[step]["mean"].get<double>(), timing[step]["max"].get<double>())
          << leds << " " << step;
    }
  }
  EXPECT_EQ(summary["brute_force_timing"]["table_c2"].size(), 8u);
  // frames.csv: header + one row per tracked frame of the five tracking sections (the timing
  // protocol's frames are not in it).
  const int frames = accuracy["frames"].get<int>() + summary["sweep"]["frames"].get<int>() +
                     occlusion["frames"].get<int>() + summary["merged"]["frames"].get<int>() +
                     summary["body_occlusion"]["frames"].get<int>();
  EXPECT_EQ(CountLines(out.path() + "/frames.csv"), static_cast<std::size_t>(frames) + 1);
  EXPECT_TRUE(std::filesystem::exists(out.path() + "/report.html"));
}

}  // namespace
}  // namespace aperture::apps::testing
