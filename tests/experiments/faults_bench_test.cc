// The trial layout of `aperture bench faults`: repeat-major, the baseline first, every selected
// fault at each level, paired seeds within a repeat; options round-trip through JSON.
#include "experiments/faults/faults_bench.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace aperture::experiments {
namespace {

TEST(FaultsBench, TrialsCoverEveryFaultLevelOncePerRepeat) {
  FaultsBenchOptions options;
  options.repeats = 3;
  options.faults = {"gust", "frame_drop"};
  ASSERT_EQ(options.TrialsPerRepeat(), 1 + 2 * 4);
  ASSERT_EQ(options.Trials(), 27);
  std::set<std::pair<std::string, double>> seen_in_repeat;
  for (int k = 0; k < options.Trials(); ++k) {
    const FaultTrialPlan plan = PlanFaultTrial(options, k);
    EXPECT_EQ(plan.repeat, k / 9);
    const FaultTrialPlan first = PlanFaultTrial(options, plan.repeat * 9);
    EXPECT_EQ(first.fault, "none");
    // Paired: every flight of a repeat has its seed, fault draw and condition.
    EXPECT_EQ(plan.seed, first.seed);
    EXPECT_EQ(plan.fault_seed, first.fault_seed);
    EXPECT_EQ(plan.condition_items, first.condition_items);
    if (plan.repeat == 0) seen_in_repeat.insert({plan.fault, plan.level});
  }
  // Catalogue order (frame_drop before gust), levels above none.
  EXPECT_EQ(PlanFaultTrial(options, 1).fault, "frame_drop");
  EXPECT_DOUBLE_EQ(PlanFaultTrial(options, 1).level, 0.125);
  EXPECT_EQ(PlanFaultTrial(options, 8).fault, "gust");
  EXPECT_DOUBLE_EQ(PlanFaultTrial(options, 8).level, 5.0);
  EXPECT_EQ(seen_in_repeat.size(), 9u);
  EXPECT_NE(PlanFaultTrial(options, 0).seed, PlanFaultTrial(options, 9).seed);
  EXPECT_LT(PlanFaultTrial(options, 0).seed, 1ull << 63);
  EXPECT_THROW(PlanFaultTrial(options, 27), std::invalid_argument);
}

TEST(FaultsBench, AcceptanceLevelsAreTheDefaultAndTwiceIt) {
  FaultsBenchOptions options;
  options.faults = {"imu_noise"};
  options.acceptance_levels = true;
  EXPECT_EQ(options.TrialsPerRepeat(), 3);
  EXPECT_DOUBLE_EQ(PlanFaultTrial(options, 1).level, 5.5);
  EXPECT_DOUBLE_EQ(PlanFaultTrial(options, 2).level, 10.0);
  // All seven faults by default.
  options.faults.clear();
  EXPECT_EQ(options.TrialsPerRepeat(), 1 + 7 * 2);
}

TEST(FaultsBench, GapConditionsDrawThePapersInclinations) {
  FaultsBenchOptions options;
  options.faults = {"gust"};
  double max_roll = 0.0, max_pitch = 0.0;
  for (int repeat = 0; repeat < 50; ++repeat) {
    options.repeats = 50;
    const FaultTrialPlan plan = PlanFaultTrial(options, repeat * options.TrialsPerRepeat());
    ASSERT_EQ(plan.condition_items.size(), 2u);
    ASSERT_EQ(plan.condition_items[0].rfind("gap.roll_deg=", 0), 0u);
    const double roll = std::stod(plan.condition_items[0].substr(13));
    const double pitch = std::stod(plan.condition_items[1].substr(14));
    EXPECT_GE(roll, 0.0);
    EXPECT_LE(roll, 45.0);
    EXPECT_GE(pitch, 0.0);
    EXPECT_LE(pitch, 30.0);
    max_roll = std::max(max_roll, roll);
    max_pitch = std::max(max_pitch, pitch);
  }
  EXPECT_GT(max_roll, 35.0);
  EXPECT_GT(max_pitch, 22.0);
  options.scenario = "led";
  EXPECT_TRUE(PlanFaultTrial(options, 0).condition_items.empty());
}

TEST(FaultsBench, OptionsRoundTripAndBadOnesAreNamed) {
  FaultsBenchOptions options;
  options.scenario = "led";
  options.repeats = 4;
  options.seed = 9;
  options.duration_s = 8.0;
  options.faults = {"accel_bias"};
  options.acceptance_levels = true;
  options.set_items = {"mission.hold.kp=2"};
  EXPECT_EQ(FaultsBenchOptionsToJson(FaultsBenchOptionsFromJson(FaultsBenchOptionsToJson(options))),
            FaultsBenchOptionsToJson(options));
  options.faults = {"accel_bias", "accel_bias"};
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options.faults = {"wind"};
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options.faults = {};
  options.repeats = 0;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
