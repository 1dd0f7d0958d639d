#pragma once
// Random scenes for the planner's evaluation, paper D Sec. D.7.1 (Figs. D.12, D.13): a fixed
// field (area, fixed obstacles, robot start, goal) and movable obstacles placed uniformly at
// random (in the field or a region of it) where they leave the robot's start and the goal footprint
// free. The paper's scene of Fig. D.12a is not given in numbers; SlalomField is ours (see its
// comment).
#include <Eigen/Core>
#include <cstdint>
#include <utility>

#include "planning/ground_mission/ground_mission_scene.h"

namespace aperture::planning {

struct RandomMissionSceneParams {
  GroundMissionScene field;  // its movable_obstacles are replaced
  int movable_obstacles = 3;
  // The tags scenario's movable cubes (sim TagsSceneParams::movable_size_m), random yaw.
  Eigen::Vector2d movable_size_m = Eigen::Vector2d(0.18, 0.18);
  double robot_radius_m = 0.35;  // the start stays free of the obstacles grown by this
  double clearance_m = 0.05;     // extra free space around every placed obstacle
  // Where the centres are drawn; an empty box (min > max, the default) means the whole field.
  Eigen::Vector2d region_min_W = Eigen::Vector2d::Constant(1.0);
  Eigen::Vector2d region_max_W = Eigen::Vector2d::Constant(-1.0);
};

// The 4 x 6 m field of the `tags` scenario (paper D's mock-up site) with two 2.6 m walls from
// opposite sides at y = 2 m and y = 4 m: the robot (start (0.6, 0.6) m facing +y) drives a
// slalom through two 1.4 m passages to the goal at (3.4, 5.4) m. A passage is narrower than the
// robot (0.7 m) plus a cube's grown disc (0.95 m), so one cube in it blocks it.
GroundMissionScene SlalomField();

// A small 4 x 3 m field for the comparison with the exhaustive search: a wall at x = 2 m from
// the south border up to y = 1.6 m leaves one 1.4 m passage in the north between the start
// (0.6, 0.6) m and the goal (3.4, 0.6) m; PassageRegion() is the box around that passage where
// the movable obstacles are drawn, so that most scenes block it and the order of removals counts.
GroundMissionScene PassageField();
std::pair<Eigen::Vector2d, Eigen::Vector2d> PassageRegion();

// Movable obstacles drawn for `seed` (std::mt19937_64): centres uniform in the field, each at
// least clearance_m off the fixed obstacles, the border, the goal footprint and the other
// obstacles, and off the robot start by robot_radius_m + clearance_m. std::runtime_error when
// 10000 draws do not place them all (field too crowded).
GroundMissionScene RandomMissionScene(const RandomMissionSceneParams& params, std::uint64_t seed);

}  // namespace aperture::planning
