// Trial randomization of `aperture bench gap`: deterministic per (seed, index), inside the ranges,
// and applied to the scenario and the SITL.
#include "experiments/gap/gap_trial_config.h"

#include <gtest/gtest.h>

#include <set>

namespace aperture::experiments {
namespace {

const Eigen::Vector3d kNominalStart(0.0, 0.0, 1.5);

TEST(DrawGapTrial, IsAPureFunctionOfSeedAndIndex) {
  const GapTrialRanges ranges;
  const GapTrialConfig a = DrawGapTrial(ranges, 7, 3, kNominalStart);
  const GapTrialConfig b = DrawGapTrial(ranges, 7, 3, kNominalStart);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.roll_deg, b.roll_deg);
  EXPECT_EQ(a.pitch_deg, b.pitch_deg);
  EXPECT_EQ(a.start_p_W, b.start_p_W);
  EXPECT_EQ(a.accel_bias_B, b.accel_bias_B);
  EXPECT_EQ(a.exposure_s, b.exposure_s);
  // Another index or another bench seed gives another trial.
  EXPECT_NE(DrawGapTrial(ranges, 7, 4, kNominalStart).roll_deg, a.roll_deg);
  EXPECT_NE(DrawGapTrial(ranges, 8, 3, kNominalStart).roll_deg, a.roll_deg);
  std::set<std::uint64_t> seeds;
  for (int i = 0; i < 1000; ++i) seeds.insert(DrawGapTrial(ranges, 7, i, kNominalStart).seed);
  EXPECT_EQ(seeds.size(), 1000u);
}

TEST(DrawGapTrial, StaysInsideTheRangesAndCoversThem) {
  GapTrialRanges ranges;
  ranges.max_roll_deg = 60.0;  // --max-roll-deg beyond the paper's 45
  ranges.max_pitch_deg = 20.0;
  double max_roll = 0.0, max_pitch = 0.0, min_roll = 90.0;
  for (int i = 0; i < 1000; ++i) {
    const GapTrialConfig t = DrawGapTrial(ranges, 1, i, kNominalStart);
    EXPECT_EQ(t.index, i);
    ASSERT_GE(t.roll_deg, 0.0);
    ASSERT_LE(t.roll_deg, 60.0);
    ASSERT_GE(t.pitch_deg, 0.0);
    ASSERT_LE(t.pitch_deg, 20.0);
    ASSERT_LE((t.start_p_W - kNominalStart).cwiseAbs().cwiseQuotient(ranges.start_offset_m).maxCoeff(),
              1.0);
    ASSERT_LE(std::abs(t.start_yaw_deg), ranges.max_start_yaw_deg);
    ASSERT_GE(t.imu_noise_scale, ranges.imu_noise_scale.x());
    ASSERT_LE(t.imu_noise_scale, ranges.imu_noise_scale.y());
    ASSERT_GE(t.drop_probability, 0.0);
    ASSERT_LE(t.drop_probability, ranges.max_drop_probability);
    ASSERT_GE(t.exposure_s, ranges.exposure_s.x());
    ASSERT_LE(t.exposure_s, ranges.exposure_s.y());
    EXPECT_EQ(t.motion_blur_subframes, ranges.motion_blur_subframes);
    max_roll = std::max(max_roll, t.roll_deg);
    min_roll = std::min(min_roll, t.roll_deg);
    max_pitch = std::max(max_pitch, t.pitch_deg);
  }
  // 1000 uniform draws come within 1 % of the range ends with probability > 1 - 2e-4.
  EXPECT_GT(max_roll, 59.4);
  EXPECT_LT(min_roll, 0.6);
  EXPECT_GT(max_pitch, 19.8);
}

TEST(DrawGapTrial, AMinimumRollDrawsTheSteepRangeAloneAndKeepsTheOtherDraws) {
  GapTrialRanges steep;
  steep.min_roll_deg = 45.0;
  steep.max_roll_deg = 60.0;
  double lowest = 90.0;
  for (int i = 0; i < 1000; ++i) {
    const GapTrialConfig t = DrawGapTrial(steep, 1, i, kNominalStart);
    ASSERT_GE(t.roll_deg, 45.0);
    ASSERT_LE(t.roll_deg, 60.0);
    lowest = std::min(lowest, t.roll_deg);
    // Only the roll's range moved: the same unit draw, the same everything else.
    GapTrialRanges full = steep;
    full.min_roll_deg = 0.0;
    const GapTrialConfig u = DrawGapTrial(full, 1, i, kNominalStart);
    ASSERT_NEAR(t.roll_deg, 45.0 + u.roll_deg * 15.0 / 60.0, 1e-9);
    ASSERT_EQ(t.pitch_deg, u.pitch_deg);
    ASSERT_EQ(t.accel_bias_B, u.accel_bias_B);
  }
  EXPECT_LT(lowest, 45.15);
}

TEST(DrawGapTrial, RejectsInvalidRanges) {
  GapTrialRanges ranges;
  ranges.min_roll_deg = 50.0;
  ranges.max_roll_deg = 40.0;
  EXPECT_THROW(DrawGapTrial(ranges, 1, 0, kNominalStart), std::invalid_argument);
  ranges = GapTrialRanges{};
  ranges.max_drop_probability = 1.0;
  EXPECT_THROW(DrawGapTrial(ranges, 1, 0, kNominalStart), std::invalid_argument);
  ranges = GapTrialRanges{};
  ranges.exposure_s = Eigen::Vector2d(0.004, 0.001);
  EXPECT_THROW(DrawGapTrial(ranges, 1, 0, kNominalStart), std::invalid_argument);
  EXPECT_THROW(DrawGapTrial(GapTrialRanges{}, 1, -1, kNominalStart), std::invalid_argument);
}

TEST(ApplyGapTrial, SetsTheScenarioAndTheSitl) {
  GapTrialConfig trial = DrawGapTrial(GapTrialRanges{}, 5, 2, kNominalStart);
  sim::ScenarioParams scenario;
  scenario.cameras.push_back({"front", sim::CameraParams{}});
  ApplyGapTrial(trial, &scenario);
  EXPECT_EQ(scenario.seed, trial.seed);
  EXPECT_EQ(scenario.gap.roll_deg, trial.roll_deg);
  EXPECT_EQ(scenario.gap.pitch_deg, trial.pitch_deg);
  EXPECT_EQ(scenario.vehicle_start.p_m, trial.start_p_W);
  EXPECT_EQ(scenario.vehicle_start.rpy_deg.z(), trial.start_yaw_deg);
  EXPECT_EQ(scenario.cameras[0].second.exposure_s, trial.exposure_s);
  EXPECT_EQ(scenario.cameras[0].second.motion_blur_subframes, trial.motion_blur_subframes);

  sim::SitlRunnerParams sitl;
  sitl.cameras.resize(2);
  const sim::ImuSensorParams nominal = sitl.imu;
  ApplyGapTrial(trial, &sitl);
  EXPECT_DOUBLE_EQ(sitl.imu.accel_noise_density, nominal.accel_noise_density * trial.imu_noise_scale);
  EXPECT_DOUBLE_EQ(sitl.imu.gyro_bias_random_walk,
                   nominal.gyro_bias_random_walk * trial.imu_noise_scale);
  EXPECT_EQ(sitl.imu.accel_bias_initial_B, trial.accel_bias_B);
  EXPECT_EQ(sitl.imu.gyro_bias_initial_B, trial.gyro_bias_B);
  for (const sim::SitlCamera& camera : sitl.cameras) {
    EXPECT_EQ(camera.drop_probability, trial.drop_probability);
  }
  // Every stream is seeded from the trial: a different trial seeds the IMU differently.
  sim::SitlRunnerParams other;
  ApplyGapTrial(DrawGapTrial(GapTrialRanges{}, 5, 3, kNominalStart), &other);
  EXPECT_NE(other.imu.seed, sitl.imu.seed);
}

}  // namespace
}  // namespace aperture::experiments
