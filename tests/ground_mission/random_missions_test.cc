// Alg. 2 over random scenes (paper D Sec. D.7.1, Figs. D.12/D.13): equal to the exhaustive search
// over every order of every subset of the movable obstacles, and solving (almost) every scene,
// each mission checked for collisions in continuous geometry, independently of the grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>

#include "planning/ground_mission/ground_mission_planner.h"
#include "planning/ground_mission/random_mission_scene.h"
#include "tests/support/ground_mission_checks.h"

namespace aperture::planning {
namespace {

RandomMissionSceneParams SceneParams(int movable_obstacles) {
  RandomMissionSceneParams params;
  params.field = SlalomField();
  params.movable_obstacles = movable_obstacles;
  return params;
}

// >= 100 small scenes (PassageField, 2-4 movable obstacles around its passage: up to 65 orders):
// Alg. 2's mission costs exactly what the best order costs. Both evaluate an order with the same
// legs and place search, so the costs are equal to rounding, not just close.
TEST(RandomMissionsTest, EqualsExhaustiveSearchOnSmallScenes) {
  int with_removals = 0;
  int with_several_removals = 0;
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    RandomMissionSceneParams params = SceneParams(2 + static_cast<int>(seed % 3));
    params.field = PassageField();
    std::tie(params.region_min_W, params.region_max_W) = PassageRegion();
    const GroundMissionScene scene = RandomMissionScene(params, seed);
    const GroundMissionPlanner planner(scene);
    const GroundMission planned = planner.Plan();
    const GroundMission exhaustive = planner.PlanExhaustively();
    ASSERT_EQ(planned.solved(), exhaustive.solved()) << "seed " << seed;
    if (!planned.solved()) continue;
    EXPECT_NEAR(planned.cost_s, exhaustive.cost_s, 1e-9)
        << "seed " << seed << "\nAlg. 2:     " << planned << "\nexhaustive: " << exhaustive;
    EXPECT_LE(planned.missions_expanded, exhaustive.missions_expanded) << "seed " << seed;
    with_removals += planned.removals.empty() ? 0 : 1;
    with_several_removals += planned.removals.size() >= 2 ? 1 : 0;
  }
  // The comparison means something only if removals happen, and orders of several (69 and 24 of
  // the 100 scenes when written).
  EXPECT_GE(with_removals, 50);
  EXPECT_GE(with_several_removals, 15);
}

// Fig. D.13's 250 scenes: 50 per number of movable obstacles 2, 4, 6, 8, 10 on the slalom field.
// The paper's planner failed on 2 of its 250; we require >= 99 % solved, each mission collision
// free.
TEST(RandomMissionsTest, SolvesAtLeast99PercentOf250Scenes) {
  const GroundMissionParams params;
  int solved = 0;
  int removals = 0;
  for (const int movable : {2, 4, 6, 8, 10}) {
    for (std::uint64_t trial = 0; trial < 50; ++trial) {
      const std::uint64_t seed = 1000 * static_cast<std::uint64_t>(movable) + trial;
      const GroundMissionScene scene = RandomMissionScene(SceneParams(movable), seed);
      const GroundMission mission = GroundMissionPlanner(scene, params).Plan();
      if (!mission.solved()) continue;
      ++solved;
      removals += static_cast<int>(mission.removals.size());
      testing::ExpectCollisionFree(scene, params, mission);
    }
  }
  EXPECT_GE(solved, 248) << solved << " of 250 solved";
  // The places are exercised: ~200 removals over the 250 missions when written.
  EXPECT_GE(removals, 100);
}

TEST(RandomMissionsTest, SceneKeepsTheStartAndTheGoalFree) {
  const RandomMissionSceneParams params = SceneParams(6);
  const GroundMissionScene scene = RandomMissionScene(params, 7);
  ASSERT_EQ(scene.movable_obstacles.size(), 6u);
  for (const GroundBox& box : scene.movable_obstacles) {
    const double radius_m = CircumscribedRadius(box);
    EXPECT_GE((box.p_W - scene.robot_p_W).norm(), radius_m + params.robot_radius_m);
    EXPECT_GE((box.p_W - scene.goal_p_W).norm(), radius_m + scene.goal_radius_m);
    for (const GroundBox& fixed : scene.fixed_obstacles) {
      EXPECT_GE(DistanceToBox(fixed, box.p_W), radius_m);
    }
  }
  // Same seed, same scene.
  EXPECT_EQ(RandomMissionScene(params, 7).movable_obstacles[3].p_W, scene.movable_obstacles[3].p_W);
  EXPECT_THROW(RandomMissionScene(SceneParams(400), 1), std::runtime_error);
}

}  // namespace
}  // namespace aperture::planning
