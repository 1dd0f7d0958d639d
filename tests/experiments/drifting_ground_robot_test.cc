// The simulated ground robot of paper D (experiments/tags/drifting_ground_robot.h): without drift
// it is the plan; its wheels drift per segment, the drift accumulates open loop and is removed by
// the fixes between segments; without fixes, or with a fix far from its odometry, it stops for
// good (fail-safe, D.7.2); obstacles it carries ride with its true pose.
#include "experiments/tags/drifting_ground_robot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "planning/ground_mission/ground_mission_planner.h"
#include "tests/support/paper_mission_scenes.h"

namespace aperture::experiments {
namespace {

constexpr double kStepS = 0.02;

struct PlannedMission {
  planning::GroundMissionScene scene = planning::testing::Figure10Scene();
  planning::GroundMissionParams params;
  planning::GroundMission mission;
  std::unique_ptr<planning::GroundMissionTimeline> timeline;
  PlannedMission() {
    params.driving_speed_mps = 0.3;
    mission = planning::GroundMissionPlanner(scene, params).Plan();
    timeline = std::make_unique<planning::GroundMissionTimeline>(mission, scene, params);
  }
};

// Runs the robot from t = 0 until it is done or stopped (or twice the plan's duration), calling
// `each` after every step; fixes of its true pose (with `fix_offset_W` added) when `fixes`.
void Execute(DriftingGroundRobot* robot, double duration_s, bool fixes,
             const Eigen::Vector2d& fix_offset_W = Eigen::Vector2d::Zero(),
             const std::function<void(double)>& each = {}) {
  robot->Start(0.0);
  std::optional<GroundRobotFix> fix;
  for (double t_s = kStepS; t_s < 2 * duration_s + 10.0; t_s += kStepS) {
    robot->Advance(t_s, fix);
    if (each) each(t_s);
    if (robot->state() == GroundRobotState::kDone ||
        robot->state() == GroundRobotState::kFailSafe) {
      return;
    }
    const planning::GroundRobotSample now = robot->Now();
    if (fixes) fix = GroundRobotFix{t_s, now.robot_p_W + fix_offset_W, now.robot_yaw_rad};
  }
}

double FinalErrorM(const DriftingGroundRobot& robot, const planning::GroundMissionTimeline& plan) {
  return (robot.Now().robot_p_W - plan.Sample(plan.duration_s()).robot_p_W).norm();
}

TEST(DriftingGroundRobot, WithoutDriftItIsThePlanAndStopsOncePerSegmentForAFix) {
  const PlannedMission m;
  ASSERT_TRUE(m.mission.solved());
  ASSERT_GE(m.mission.removals.size(), 1u);
  DriftingGroundRobot robot(*m.timeline, {0.0, 0.0}, {}, 1);
  Execute(&robot, m.timeline->duration_s(), true, Eigen::Vector2d::Zero(), [&](double) {
    const planning::GroundRobotSample now = robot.Now();
    const planning::GroundRobotSample plan = m.timeline->Sample(robot.execution_s());
    ASSERT_LT((now.robot_p_W - plan.robot_p_W).norm(), 1e-9);
    for (size_t k = 0; k < plan.movable_p_W.size(); ++k) {
      ASSERT_LT((now.movable_p_W[k] - plan.movable_p_W[k]).norm(), 1e-9);
    }
  });
  EXPECT_EQ(robot.state(), GroundRobotState::kDone);
  EXPECT_DOUBLE_EQ(robot.execution_s(), m.timeline->duration_s());
  // One fix per open-loop command: the drive segments, cut into pieces of at most 1 m.
  ASSERT_GT(robot.commands().size(), m.timeline->DriveSegments().size());
  for (const planning::GroundDriveSegment& command : robot.commands()) {
    EXPECT_LE((command.end_s - command.start_s) * m.params.driving_speed_mps, 1.0 + 1e-9);
  }
  EXPECT_EQ(robot.relocalizations().size(), robot.commands().size());
  for (const GroundRelocalization& r : robot.relocalizations()) EXPECT_LT(r.correction_m, 1e-9);
}

TEST(DriftingGroundRobot, ADistanceErrorAloneKeepsTheFirstSegmentOnItsLine) {
  const PlannedMission m;
  const planning::GroundDriveSegment first = m.timeline->DriveSegments().front();
  const Eigen::Vector2d a = m.timeline->Sample(first.start_s).robot_p_W;
  const Eigen::Vector2d b = m.timeline->Sample(first.end_s).robot_p_W;
  GroundRelocalizationParams open_loop;
  open_loop.enabled = false;
  DriftingGroundRobot robot(*m.timeline, {0.2, 0.0}, open_loop, 3);
  double max_off_line_m = 0.0;
  bool moved_off_plan = false;
  Execute(&robot, m.timeline->duration_s(), false, Eigen::Vector2d::Zero(), [&](double) {
    if (robot.execution_s() > first.end_s) return;
    const Eigen::Vector2d p = robot.Now().robot_p_W - a;
    const Eigen::Vector2d u = (b - a).normalized();
    max_off_line_m = std::max(max_off_line_m, std::abs(u.x() * p.y() - u.y() * p.x()));
    moved_off_plan |=
        (robot.Now().robot_p_W - m.timeline->Sample(robot.execution_s()).robot_p_W).norm() > 1e-3;
  });
  EXPECT_LT(max_off_line_m, 1e-9);
  EXPECT_TRUE(moved_off_plan);  // 20 % of a distance error shows along the line
}

TEST(DriftingGroundRobot, FixesBetweenSegmentsRemoveTheDriftThatAccumulatesOpenLoop) {
  const PlannedMission m;
  const GroundOdometryDriftParams drift{0.05, 0.05};
  GroundRelocalizationParams open_loop;
  open_loop.enabled = false;
  double open_loop_sum_m = 0.0, relocalized_sum_m = 0.0, relocalized_max_m = 0.0;
  constexpr int kSeeds = 20;
  for (int seed = 0; seed < kSeeds; ++seed) {
    DriftingGroundRobot drifting(*m.timeline, drift, open_loop, seed);
    Execute(&drifting, m.timeline->duration_s(), false);
    ASSERT_EQ(drifting.state(), GroundRobotState::kDone);
    open_loop_sum_m += FinalErrorM(drifting, *m.timeline);
    DriftingGroundRobot relocalized(*m.timeline, drift, {}, seed);
    Execute(&relocalized, m.timeline->duration_s(), true);
    ASSERT_EQ(relocalized.state(), GroundRobotState::kDone) << relocalized.fail_reason();
    relocalized_sum_m += FinalErrorM(relocalized, *m.timeline);
    relocalized_max_m = std::max(relocalized_max_m, FinalErrorM(relocalized, *m.timeline));
  }
  // With fixes only the last segment's drift remains: its length (< the field's 6 m) times the
  // errors, a few centimetres; open loop every segment's adds up.
  EXPECT_LT(relocalized_max_m, 0.15);
  EXPECT_GT(open_loop_sum_m, 3 * relocalized_sum_m)
      << "open loop " << open_loop_sum_m / kSeeds << " m, relocalized "
      << relocalized_sum_m / kSeeds << " m (mean final error)";
}

TEST(DriftingGroundRobot, WithoutAFixItStopsForGoodAtTheFirstSegmentsEnd) {
  const PlannedMission m;
  GroundRelocalizationParams relocalization;
  relocalization.fix_timeout_s = 2.0;
  DriftingGroundRobot robot(*m.timeline, {}, relocalization, 1);
  Execute(&robot, m.timeline->duration_s(), false);
  EXPECT_EQ(robot.state(), GroundRobotState::kFailSafe);
  EXPECT_NE(robot.fail_reason().find("communication"), std::string::npos) << robot.fail_reason();
  EXPECT_DOUBLE_EQ(robot.execution_s(), robot.commands().front().end_s);
  const Eigen::Vector2d stopped_W = robot.Now().robot_p_W;
  robot.Advance(1e3, GroundRobotFix{1e3, stopped_W, 0.0});
  EXPECT_EQ(robot.state(), GroundRobotState::kFailSafe);
  EXPECT_EQ(robot.Now().robot_p_W, stopped_W);
}

TEST(DriftingGroundRobot, AFixFarFromTheOdometryIsAMappingErrorAndStopsIt) {
  const PlannedMission m;
  DriftingGroundRobot robot(*m.timeline, {0.0, 0.0}, {}, 1);
  Execute(&robot, m.timeline->duration_s(), true, Eigen::Vector2d(0.4, 0.0));
  EXPECT_EQ(robot.state(), GroundRobotState::kFailSafe);
  EXPECT_NE(robot.fail_reason().find("mapping"), std::string::npos) << robot.fail_reason();
  ASSERT_EQ(robot.relocalizations().size(), 1u);
  EXPECT_NEAR(robot.relocalizations()[0].correction_m, 0.4, 1e-9);
}

TEST(DriftingGroundRobot, ACarriedObstacleRidesWithTheTruePoseAndStaysWhereItWasPlaced) {
  const PlannedMission m;
  GroundRelocalizationParams open_loop;
  open_loop.enabled = false;
  DriftingGroundRobot robot(*m.timeline, {0.05, 0.05}, open_loop, 7);
  const planning::GroundRemovalTimes first = m.timeline->removal_times().front();
  const size_t k = static_cast<size_t>(first.obstacle);
  std::optional<Eigen::Vector2d> placed_W;
  int carried_samples = 0;
  Execute(&robot, m.timeline->duration_s(), false, Eigen::Vector2d::Zero(), [&](double) {
    const double tau_s = robot.execution_s();
    const planning::GroundRobotSample now = robot.Now();
    if (tau_s > first.grasp_end_s && tau_s < first.place_start_s) {
      ++carried_samples;
      ASSERT_LT((now.movable_p_W[k] - now.robot_p_W).norm(), 1e-9);
    }
    if (tau_s >= first.place_end_s) {
      if (!placed_W) placed_W = now.movable_p_W[k];
      ASSERT_LT((now.movable_p_W[k] - *placed_W).norm(), 1e-12);
    }
  });
  EXPECT_GT(carried_samples, 0);
  ASSERT_TRUE(placed_W);
  EXPECT_GT((*placed_W - m.mission.removals.front().place_p_W).norm(), 1e-4);  // it drifted
}

}  // namespace
}  // namespace aperture::experiments
