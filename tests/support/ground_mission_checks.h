#pragma once
// Checks of a planned ground-robot mission (planning/ground_mission/) against its scene, shared
// by the ground_mission tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "planning/ground_mission/ground_mission_planner.h"

namespace aperture::planning::testing {

// The mission's collision checks against the scene, in continuous geometry. The path is
// sampled every 1 cm; the grid checks cell centres only, and a straight piece between cell
// centres passes at most half a cell diagonal (0.035 m) off the Bresenham cells it was checked
// on, hence the one-cell tolerance against the scene's obstacles. A placed obstacle must keep
// clear of the path from where the robot put it down (arc length place_s_m) on, the stretches
// driven again after carrying it back included: that the place search checks exactly, on the
// same path, so there it is checked without tolerance.
inline void ExpectCollisionFree(const GroundMissionScene& scene, const GroundMissionParams& params,
                                const GroundMission& mission) {
  const double tolerance_m = params.cell_size_m;
  // Placements first: each obstacle's disc in the field, off the fixed obstacles and off the
  // obstacles still in place and already placed when it is put down.
  std::vector<bool> removed(scene.movable_obstacles.size(), false);
  std::vector<std::pair<Eigen::Vector2d, double>> placed;
  for (const GroundObstacleRemoval& removal : mission.removals) {
    removed[static_cast<size_t>(removal.obstacle)] = true;
    const double radius_m =
        CircumscribedRadius(scene.movable_obstacles[static_cast<size_t>(removal.obstacle)]);
    const Eigen::Vector2d q = removal.place_p_W;
    ASSERT_TRUE(((q - scene.area_min_W).array() >= radius_m).all() &&
                ((scene.area_max_W - q).array() >= radius_m).all())
        << mission;
    for (const GroundBox& box : scene.fixed_obstacles) {
      ASSERT_GE(DistanceToBox(box, q), radius_m) << mission;
    }
    for (size_t m = 0; m < scene.movable_obstacles.size(); ++m) {
      if (removed[m]) continue;
      ASSERT_GE((q - scene.movable_obstacles[m].p_W).norm(),
                radius_m + CircumscribedRadius(scene.movable_obstacles[m]))
          << mission;
    }
    for (const auto& [other, other_radius_m] : placed) {
      ASSERT_GE((q - other).norm(), radius_m + other_radius_m) << mission;
    }
    // Within the gripper's reach of the robot's place position, which lies on the path driven.
    EXPECT_NEAR((q - removal.robot_at_place_p_W).norm(), params.grasp_radius_m, 1e-9);
    EXPECT_EQ(removal.backward_m, std::max(0.0, removal.grasp_s_m - removal.place_s_m));
    placed.emplace_back(q, radius_m);
  }
  // The path: an obstacle is in place until the end of the leg that grasps it.
  double s_m = 0.0;
  for (size_t leg_index = 0; leg_index < mission.legs.size(); ++leg_index) {
    const auto& waypoints = mission.legs[leg_index].waypoints;
    for (size_t i = 0; i + 1 < waypoints.size(); ++i) {
      const Eigen::Vector2d a = waypoints[i].p_W;
      const Eigen::Vector2d b = waypoints[i + 1].p_W;
      const int samples = std::max(1, static_cast<int>((b - a).norm() / 0.01));
      for (int k = 0; k <= samples; ++k) {
        const Eigen::Vector2d p = a + (b - a) * k / samples;
        const double p_s_m = s_m + (b - a).norm() * k / samples;
        for (const GroundBox& box : scene.fixed_obstacles) {
          ASSERT_GT(DistanceToBox(box, p), params.robot_radius_m - tolerance_m)
              << "leg " << leg_index << " hits a fixed obstacle: " << mission;
        }
        for (size_t m = 0; m < scene.movable_obstacles.size(); ++m) {
          const auto grasped = std::find_if(
              mission.removals.begin(),
              mission.removals.begin() +
                  static_cast<std::ptrdiff_t>(std::min(leg_index, mission.removals.size())),
              [&](const GroundObstacleRemoval& r) { return r.obstacle == static_cast<int>(m); });
          if (grasped != mission.removals.begin() + static_cast<std::ptrdiff_t>(std::min(
                                                        leg_index, mission.removals.size()))) {
            continue;
          }
          const GroundBox& box = scene.movable_obstacles[m];
          ASSERT_GT((p - box.p_W).norm(),
                    CircumscribedRadius(box) + params.robot_radius_m - tolerance_m)
              << "leg " << leg_index << " hits movable obstacle " << m << ": " << mission;
        }
        for (size_t r = 0; r < mission.removals.size(); ++r) {
          if (p_s_m < mission.removals[r].place_s_m + 1e-9) continue;
          ASSERT_GE((p - placed[r].first).norm(), placed[r].second + params.robot_radius_m - 1e-9)
              << "leg " << leg_index << " hits placed obstacle " << mission.removals[r].obstacle
              << ": " << mission;
        }
      }
      s_m += (b - a).norm();
    }
  }
  const Eigen::Vector2d end_W = mission.legs.back().waypoints.back().p_W;
  EXPECT_LE((end_W - scene.goal_p_W).norm(), params.grasp_radius_m) << mission;
  EXPECT_NEAR(mission.cost_s,
              mission.drive_s + mission.turn_s + mission.remove_s + mission.backward_s, 1e-9);
}

}  // namespace aperture::planning::testing
