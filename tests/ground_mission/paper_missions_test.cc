// The special cases of paper D Sec. D.7.1 rebuilt as scenes: the missions of Figs. D.9a, D.9b
// and D.10. The paper gives the figures as drawings without numbers; the layouts below are our
// reading of the captions and the text (D.5.1, D.7.1), with the D.7 parameters:
//   D.9   a fixed block between start (west) and goal (east) leaves a narrow south corridor
//         (0.9 m: the robot passes, nothing can be placed beside it) and a longer, wider north
//         corridor (1.5 m: a cube fits beside the robot), each blocked by one movable cube.
//         (a) the planner takes the north corridor: removing its cube needs no backward
//         driving, while the south cube must be carried back out of its corridor; the south
//         path is shorter. (b) a fixed wall closes the north corridor: the south corridor is
//         taken, the cube carried back out of it, and the mission takes longer than (a).
//   D.10  one 0.9 m corridor, the only way to the goal, holding three cubes: the first two are
//         carried back to the corridor entrance, the last is placed at its exit.
#include <gtest/gtest.h>

#include "planning/ground_mission/ground_mission_planner.h"
#include "tests/support/ground_mission_checks.h"
#include "tests/support/paper_mission_scenes.h"

namespace aperture::planning {
namespace {

using testing::Cube;
using testing::Figure10Scene;
using testing::Figure9aScene;
using testing::Figure9bScene;

// The corridors of Figs. D.9 and D.10 end at x = 1.5 m (entrance) and 4.5 m (exit); a cube
// placed outside lies at least its radius off them.
constexpr double kCorridorEntrance_m = 1.5;
constexpr double kCorridorExit_m = 4.5;

TEST(PaperMissionsTest, Figure9aTakesTheNorthPathWithoutBackwardDriving) {
  const GroundMissionPlanner planner(Figure9aScene());
  const GroundMission mission = planner.Plan();
  ASSERT_TRUE(mission.solved()) << mission;
  EXPECT_EQ(mission.Order(), std::vector<int>({2, 3})) << mission;
  EXPECT_EQ(mission.backward_s, 0.0) << mission;
  testing::ExpectCollisionFree(planner.scene(), planner.params(), mission);
  // The south mission: shorter path, but the first cube is carried back out of the corridor.
  const GroundMission south = planner.EvaluateOrder({0, 1});
  ASSERT_TRUE(south.solved()) << south;
  EXPECT_LT(south.path_length_m(), mission.path_length_m() - 1.0) << south;
  EXPECT_GT(south.removals[0].backward_m, 1.0) << south;
  EXPECT_GT(south.cost_s, mission.cost_s) << south;
  EXPECT_DOUBLE_EQ(planner.PlanExhaustively().cost_s, mission.cost_s);
}

TEST(PaperMissionsTest, Figure9bTakesTheSouthPathAndCarriesTheFirstCubeBack) {
  const GroundMissionPlanner planner(Figure9bScene());
  const GroundMission mission = planner.Plan();
  ASSERT_TRUE(mission.solved()) << mission;
  ASSERT_EQ(mission.Order(), std::vector<int>({0, 1})) << mission;
  // The first cube goes back out of the corridor's entrance, the second beyond its exit.
  EXPECT_GT(mission.removals[0].backward_m, 1.0) << mission;
  EXPECT_LT(mission.removals[0].place_p_W.x(), kCorridorEntrance_m) << mission;
  EXPECT_EQ(mission.removals[1].backward_m, 0.0) << mission;
  EXPECT_GT(mission.removals[1].place_p_W.x(), kCorridorExit_m) << mission;
  testing::ExpectCollisionFree(planner.scene(), planner.params(), mission);
  // The caption: this mission takes longer than the one of Fig. D.9a.
  EXPECT_GT(mission.cost_s, GroundMissionPlanner(Figure9aScene()).Plan().cost_s);
  EXPECT_DOUBLE_EQ(planner.PlanExhaustively().cost_s, mission.cost_s);
}

TEST(PaperMissionsTest, Figure10CarriesAllButTheLastCubeBack) {
  const GroundMissionPlanner planner(Figure10Scene());
  const GroundMission mission = planner.Plan();
  ASSERT_TRUE(mission.solved()) << mission;
  ASSERT_EQ(mission.Order(), std::vector<int>({0, 1, 2})) << mission;
  for (int i = 0; i < 2; ++i) {
    EXPECT_GT(mission.removals[i].backward_m, 0.0) << "removal " << i << ": " << mission;
    EXPECT_LT(mission.removals[i].place_p_W.x(), kCorridorEntrance_m) << mission;
  }
  EXPECT_EQ(mission.removals[2].backward_m, 0.0) << mission;
  EXPECT_GT(mission.removals[2].place_p_W.x(), kCorridorExit_m) << mission;
  // The second cube is carried back further than the first (it lies deeper in the corridor).
  EXPECT_GT(mission.removals[1].backward_m, mission.removals[0].backward_m) << mission;
  testing::ExpectCollisionFree(planner.scene(), planner.params(), mission);
  EXPECT_DOUBLE_EQ(planner.PlanExhaustively().cost_s, mission.cost_s);
}

TEST(PaperMissionsTest, FreeFieldDrivesStraightToTheGoal) {
  // No obstacle: Alg. 3 leaves the start and the delivery point, one straight line whose length
  // is the distance to the goal less the grasp radius (to within a cell), at the D.7 speed.
  GroundMissionScene scene;
  scene.area_max_W = Eigen::Vector2d(6.0, 4.0);
  scene.robot_p_W = Eigen::Vector2d(1.025, 2.025);  // a cell centre
  scene.goal_p_W = Eigen::Vector2d(5.025, 2.025);
  const GroundMissionParams params;
  const GroundMission mission = GroundMissionPlanner(scene, params).Plan();
  ASSERT_TRUE(mission.solved()) << mission;
  ASSERT_EQ(mission.legs.size(), 1u);
  EXPECT_EQ(mission.legs[0].waypoints.size(), 2u);
  EXPECT_NEAR(mission.path_length_m(), 4.0 - params.grasp_radius_m, params.cell_size_m);
  EXPECT_DOUBLE_EQ(mission.cost_s, mission.path_length_m() / params.driving_speed_mps);
  EXPECT_EQ(mission.turn_s, 0.0);
}

TEST(PaperMissionsTest, RemovalTimeDecidesBetweenDetourAndRemoval) {
  // Fig. D.11's point: a cube closes the short way (the south corridor of D.9b's block, whose
  // north corridor is open here); the long way round costs a fixed detour. With a quick removal
  // the cube is removed, with a slow one the robot drives around.
  GroundMissionScene scene = Figure9aScene();
  scene.movable_obstacles = {Cube(4.2, 0.45)};  // last in the corridor: placed at its exit
  GroundMissionParams quick;
  quick.remove_time_s = 1.0;
  GroundMissionParams slow;
  slow.remove_time_s = 60.0;
  EXPECT_EQ(GroundMissionPlanner(scene, quick).Plan().Order(), std::vector<int>({0}));
  EXPECT_TRUE(GroundMissionPlanner(scene, slow).Plan().Order().empty());
}

TEST(PaperMissionsTest, RejectsACollidingStartAndBadParameters) {
  GroundMissionScene scene = Figure9aScene();
  scene.robot_p_W = Eigen::Vector2d(3.0, 1.7);  // inside the block
  EXPECT_THROW(GroundMissionPlanner{scene}, std::invalid_argument);
  GroundMissionParams params;
  params.grasp_radius_m = 0.4;  // below robot radius + cube radius
  EXPECT_THROW(GroundMissionPlanner(Figure9aScene(), params), std::invalid_argument);
  GroundMissionParams standing;
  standing.driving_speed_mps = 0.0;
  EXPECT_THROW(GroundMissionPlanner(Figure9aScene(), standing), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
