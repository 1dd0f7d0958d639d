// The forest evaluator on constructed flights: success needs the goal radius and no collision,
// and time to the goal, path length and clearance equal their analytic values.
#include "experiments/missions/forest_evaluation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace aperture::experiments {
namespace {

using ::testing::HasSubstr;

// A straight flight along x at height 1.5 m and lateral offset y_m, from x = 0 to x_end_m at
// 1 m/s, sampled every 1 ms.
std::vector<control::QuadState> StraightForestFlight(double x_end_m, double y_m) {
  std::vector<control::QuadState> trajectory;
  for (int k = 0; k <= static_cast<int>(std::lround(x_end_m * 1000)); ++k) {
    control::QuadState x;
    x.t_s = k * 1e-3;
    x.p_WB = Eigen::Vector3d(k * 1e-3, y_m, 1.5);
    x.v_W = Eigen::Vector3d::UnitX();
    trajectory.push_back(x);
  }
  return trajectory;
}

sim::Scene OneTrunk() {
  sim::Scene scene;
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.translation() = Eigen::Vector3d(5.0, 0.0, 0.0);
  scene.AddObject({"trunk", sim::Cylinder{0.3, 5.0}, {}, T_WO});
  scene.AddObject({"ground", sim::GroundPlane{}, {}, Eigen::Isometry3d::Identity()});
  return scene;
}

TEST(ForestEvaluation, ReachedWithoutCollisionPassesWithTheAnalyticFigures) {
  const sim::Scene scene = OneTrunk();
  const Eigen::Vector3d goal(10.0, 1.0, 1.5);
  const ForestEvaluation e = EvaluateForestFlight(StraightForestFlight(10.0, 1.0), {}, goal, scene);
  EXPECT_TRUE(e.success);
  EXPECT_TRUE(e.reached_goal);
  // First sample within 1 m of the goal: x = 9 m at 1 m/s.
  EXPECT_NEAR(e.time_to_goal_s, 9.0, 1.5e-3);
  EXPECT_NEAR(e.path_length_m, 9.0, 1.5e-3);
  // Passing the trunk axis 1 m away: 1 - 0.3 m to its surface; the ground does not count.
  EXPECT_NEAR(e.min_clearance_m, 0.7, 1e-9);
  EXPECT_EQ(e.nearest_obstacle, "trunk");
  EXPECT_NEAR(e.final_distance_m, 0.0, 1e-9);
  EXPECT_TRUE(e.failure_reason.empty());
}

TEST(ForestEvaluation, ACollisionOrAMissedGoalFails) {
  const sim::Scene scene = OneTrunk();
  const Eigen::Vector3d goal(10.0, 1.0, 1.5);
  const ForestEvaluation crashed = EvaluateForestFlight(
      StraightForestFlight(10.0, 1.0), std::string("collision: body with 'trunk'"), goal, scene);
  EXPECT_FALSE(crashed.success);
  EXPECT_TRUE(crashed.reached_goal);
  EXPECT_THAT(crashed.failure_reason, HasSubstr("trunk"));

  // Stops at x = 8.9 m: 1.1 m short, just outside the radius.
  const ForestEvaluation short_of_goal =
      EvaluateForestFlight(StraightForestFlight(8.9, 1.0), {}, goal, scene);
  EXPECT_FALSE(short_of_goal.success);
  EXPECT_FALSE(short_of_goal.reached_goal);
  EXPECT_TRUE(std::isnan(short_of_goal.time_to_goal_s));
  EXPECT_NEAR(short_of_goal.final_distance_m, 1.1, 1e-9);
  EXPECT_NEAR(short_of_goal.path_length_m, 8.9, 1e-9);
  EXPECT_THAT(short_of_goal.failure_reason, HasSubstr("goal radius"));
}

TEST(ForestEvaluation, DistanceToObjectIsTheDistanceToTheSolid) {
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.linear() = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_WO.translation() = Eigen::Vector3d(2.0, 0.0, 0.5);
  const sim::SceneObject box{"box", sim::Box{Eigen::Vector3d::Constant(1.0)}, {}, T_WO};
  // Along the box's diagonal direction in the plane: the corner is sqrt(2)/2 from the centre.
  EXPECT_NEAR(DistanceToObject(box, Eigen::Vector3d(2.0 + 1.0, 0.0, 0.5)),
              // point (1,0) in W is (cos45, -sin45) in O: excess over 0.5 per axis
              std::sqrt(2.0) * (std::sqrt(0.5) - 0.5), 1e-12);
  EXPECT_EQ(DistanceToObject(box, Eigen::Vector3d(2.0, 0.0, 0.5)), 0.0);  // inside
  const sim::SceneObject trunk{"trunk", sim::Cylinder{0.2, 3.0}, {}, Eigen::Isometry3d::Identity()};
  EXPECT_NEAR(DistanceToObject(trunk, Eigen::Vector3d(0.0, 1.0, 1.0)), 0.8, 1e-12);
  EXPECT_NEAR(DistanceToObject(trunk, Eigen::Vector3d(0.0, 0.0, 4.0)), 1.0, 1e-12);  // above
  EXPECT_NEAR(DistanceToObject(trunk, Eigen::Vector3d(0.5, 0.0, 4.0)), std::hypot(0.3, 1.0), 1e-12);
  const sim::SceneObject ground{"ground", sim::GroundPlane{}, {}, Eigen::Isometry3d::Identity()};
  EXPECT_TRUE(std::isinf(DistanceToObject(ground, Eigen::Vector3d(0, 0, 1))));
}

TEST(ForestEvaluation, RejectsAnEmptyTrajectory) {
  EXPECT_THROW(EvaluateForestFlight({}, {}, Eigen::Vector3d::Zero(), OneTrunk()),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
