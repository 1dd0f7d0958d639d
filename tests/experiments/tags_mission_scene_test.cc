// The `tags` scenario's objects as the ground-robot planner's scene (experiments/tags/
// tags_mission_scene.h): footprints at the true object poses, and a plan for the field.
#include "experiments/tags/tags_mission_scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "control/constants.h"
#include "planning/ground_mission/ground_mission_planner.h"
#include "sim/scenario/scenario.h"

namespace aperture::experiments {
namespace {

TEST(TagsMissionSceneTest, FootprintsSitAtTheObjectsAndThePlanReachesTheGoal) {
  const sim::Scenario scenario =
      sim::BuildScenario(sim::LoadScenarioParams(sim::ScenarioConfig("tags")));
  const sim::TagsSceneParams& field = scenario.params().tags;
  const planning::GroundMissionScene scene =
      TagsMissionScene(field, TagsScenarioTagPoses(scenario));
  ASSERT_EQ(static_cast<int>(scene.fixed_obstacles.size()), field.fixed_obstacles);
  ASSERT_EQ(static_cast<int>(scene.movable_obstacles.size()), field.movable_obstacles);
  EXPECT_TRUE(scene.area_max_W.isApprox(field.area_m));
  EXPECT_TRUE(scene.goal_p_W.isApprox(field.goal_xy_m, 1e-12));
  const auto expect_at = [&](const planning::GroundBox& box, const std::string& name) {
    const Eigen::Isometry3d& T_WO = scenario.scene().object(name).T_WO;
    EXPECT_TRUE(box.p_W.isApprox(T_WO.translation().head<2>(), 1e-9)) << name;
    const Eigen::Vector3d x_W = T_WO.rotation().col(0);
    EXPECT_NEAR(std::remainder(box.yaw_rad - std::atan2(x_W.y(), x_W.x()), 2 * control::kPi), 0.0,
                1e-9)
        << name;
  };
  for (int k = 0; k < field.fixed_obstacles; ++k) {
    expect_at(scene.fixed_obstacles[static_cast<size_t>(k)], "fixed" + std::to_string(k));
  }
  for (int k = 0; k < field.movable_obstacles; ++k) {
    expect_at(scene.movable_obstacles[static_cast<size_t>(k)], "movable" + std::to_string(k));
  }
  const Eigen::Isometry3d& T_W_robot = scenario.scene().object("robot").T_WO;
  EXPECT_TRUE(scene.robot_p_W.isApprox(T_W_robot.translation().head<2>(), 1e-9));
  const planning::GroundMission mission = planning::GroundMissionPlanner(scene).Plan();
  ASSERT_TRUE(mission.solved()) << mission;
  EXPECT_LE((mission.legs.back().waypoints.back().p_W - scene.goal_p_W).norm(),
            planning::GroundMissionParams().grasp_radius_m);
}

TEST(TagsMissionSceneTest, MissingRobotTagIsAnError) {
  sim::TagsSceneParams field;
  std::map<int, Eigen::Isometry3d> poses{{1, Eigen::Isometry3d::Identity()}};
  EXPECT_THROW(TagsMissionScene(field, poses), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
