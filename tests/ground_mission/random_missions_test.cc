// Alg. 2 over random scenes (paper D Sec. D.7.1, Figs. D.12/D.13): equal to the exhaustive search
// over every order of every subset of the movable obstacles, and solving (almost) every scene,
// each mission checked for collisions in continuous geometry, independently of the grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <tuple>

#include "planning/ground_mission/ground_mission_planner.h"
#include "planning/ground_mission/random_mission_scene.h"

namespace aperture::planning {
namespace {

std::string Print(const GroundMission& mission) {
  std::ostringstream out;
  out << mission;
  return out.str();
}

// The mission's collision checks against the scene. Waypoint segments are sampled every 1 cm;
// the grid checks cell centres only, and a straight piece between cell centres passes at most
// half a cell diagonal (0.035 m) off the Bresenham cells it was checked on, hence the one-cell
// tolerance for the legs. The place search checks the same polyline exactly (no tolerance).
void ExpectCollisionFree(const GroundMissionScene& scene, const GroundMissionParams& params,
                         const GroundMission& mission) {
  const double tolerance_m = params.cell_size_m;
  std::vector<bool> removed(scene.movable_obstacles.size(), false);
  std::vector<std::pair<Eigen::Vector2d, double>> placed;
  for (size_t leg_index = 0; leg_index < mission.legs.size(); ++leg_index) {
    const auto& waypoints = mission.legs[leg_index].waypoints;
    for (size_t i = 0; i + 1 < waypoints.size(); ++i) {
      const Eigen::Vector2d a = waypoints[i].p_W;
      const Eigen::Vector2d b = waypoints[i + 1].p_W;
      const int samples = std::max(1, static_cast<int>((b - a).norm() / 0.01));
      for (int k = 0; k <= samples; ++k) {
        const Eigen::Vector2d p = a + (b - a) * k / samples;
        for (const GroundBox& box : scene.fixed_obstacles) {
          ASSERT_GT(DistanceToBox(box, p), params.robot_radius_m - tolerance_m)
              << "leg " << leg_index << " hits a fixed obstacle: " << Print(mission);
        }
        for (size_t m = 0; m < scene.movable_obstacles.size(); ++m) {
          if (removed[m]) continue;
          const GroundBox& box = scene.movable_obstacles[m];
          ASSERT_GT((p - box.p_W).norm(),
                    CircumscribedRadius(box) + params.robot_radius_m - tolerance_m)
              << "leg " << leg_index << " hits movable obstacle " << m << ": " << Print(mission);
        }
        for (const auto& [q, radius_m] : placed) {
          ASSERT_GE((p - q).norm(), radius_m + params.robot_radius_m - 1e-9)
              << "leg " << leg_index << " hits a placed obstacle: " << Print(mission);
        }
      }
    }
    if (leg_index >= mission.removals.size()) break;
    const GroundObstacleRemoval& removal = mission.removals[leg_index];
    removed[static_cast<size_t>(removal.obstacle)] = true;
    const double radius_m =
        CircumscribedRadius(scene.movable_obstacles[static_cast<size_t>(removal.obstacle)]);
    const Eigen::Vector2d q = removal.place_p_W;
    ASSERT_TRUE(((q - scene.area_min_W).array() >= radius_m).all() &&
                ((scene.area_max_W - q).array() >= radius_m).all())
        << Print(mission);
    for (const GroundBox& box : scene.fixed_obstacles) {
      ASSERT_GE(DistanceToBox(box, q), radius_m) << Print(mission);
    }
    for (size_t m = 0; m < scene.movable_obstacles.size(); ++m) {
      if (removed[m]) continue;
      ASSERT_GE((q - scene.movable_obstacles[m].p_W).norm(),
                radius_m + CircumscribedRadius(scene.movable_obstacles[m]))
          << Print(mission);
    }
    // Within the gripper's reach of the robot's place position, which lies on the path driven.
    EXPECT_NEAR((q - removal.robot_at_place_p_W).norm(), params.grasp_radius_m, 1e-9);
    placed.emplace_back(q, radius_m);
  }
  const Eigen::Vector2d end_W = mission.legs.back().waypoints.back().p_W;
  EXPECT_LE((end_W - scene.goal_p_W).norm(), params.grasp_radius_m) << Print(mission);
  EXPECT_NEAR(mission.cost_s,
              mission.drive_s + mission.turn_s + mission.remove_s + mission.backward_s, 1e-9);
}

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
        << "seed " << seed << "\nAlg. 2:     " << Print(planned)
        << "\nexhaustive: " << Print(exhaustive);
    EXPECT_LE(planned.missions_expanded, exhaustive.missions_expanded) << "seed " << seed;
    with_removals += planned.removals.empty() ? 0 : 1;
    with_several_removals += planned.removals.size() >= 2 ? 1 : 0;
  }
  // The comparison means something only if removals happen, and orders of several (69 and 24 of
  // the 100 scenes when written).
  EXPECT_GE(with_removals, 50);
  EXPECT_GE(with_several_removals, 15);
}

// Fig. D.13's 250 scenes: 50 per number of movable obstacles 1-5 on the slalom field. The
// paper's planner failed on 2 of its 250; we require >= 99 % solved, each mission collision free.
TEST(RandomMissionsTest, SolvesAtLeast99PercentOf250Scenes) {
  const GroundMissionParams params;
  int solved = 0;
  for (int movable = 1; movable <= 5; ++movable) {
    for (std::uint64_t trial = 0; trial < 50; ++trial) {
      const std::uint64_t seed = 1000 * static_cast<std::uint64_t>(movable) + trial;
      const GroundMissionScene scene = RandomMissionScene(SceneParams(movable), seed);
      const GroundMission mission = GroundMissionPlanner(scene, params).Plan();
      if (!mission.solved()) continue;
      ++solved;
      ExpectCollisionFree(scene, params, mission);
    }
  }
  EXPECT_GE(solved, 248) << solved << " of 250 solved";
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
