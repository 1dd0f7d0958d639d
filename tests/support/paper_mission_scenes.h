#pragma once
// The scenes of paper D's Figs. D.9a, D.9b and D.10 (seed 001, Sec. D.7.1) as we read the
// drawings (tests/ground_mission/paper_missions_test.cc says how), shared by the ground_mission
// tests.
#include <Eigen/Core>

#include "planning/ground_mission/ground_mission_scene.h"

namespace aperture::planning::testing {

inline GroundBox Cube(double x, double y) {
  return {Eigen::Vector2d(x, y), Eigen::Vector2d(0.18, 0.18), 0.0};
}

inline GroundBox Block(double x_min, double y_min, double x_max, double y_max) {
  return {Eigen::Vector2d(x_min + x_max, y_min + y_max) / 2,
          Eigen::Vector2d(x_max - x_min, y_max - y_min), 0.0};
}

// Fig. D.9a: 6 x 4 m, block x 1.5-4.5 m, y 0.9-2.5 m; south corridor y 0-0.9 m, north corridor
// y 2.5-4 m. Cube 0 in the south corridor, cube 1 in the north one.
inline GroundMissionScene Figure9aScene() {
  GroundMissionScene scene;
  scene.area_max_W = Eigen::Vector2d(6.0, 4.0);
  scene.fixed_obstacles = {Block(1.5, 0.9, 4.5, 2.5)};
  scene.movable_obstacles = {Cube(3.6, 0.45), Cube(4.2, 0.45), Cube(2.6, 3.25), Cube(3.6, 3.25)};
  scene.robot_p_W = Eigen::Vector2d(0.6, 1.0);
  scene.robot_yaw_rad = 0.0;
  scene.goal_p_W = Eigen::Vector2d(5.4, 1.0);
  return scene;
}

// Fig. D.9b: as D.9a with a fixed wall across the north corridor.
inline GroundMissionScene Figure9bScene() {
  GroundMissionScene scene = Figure9aScene();
  scene.fixed_obstacles.push_back(Block(1.9, 2.5, 2.2, 4.0));
  return scene;
}

// Fig. D.10: 6 x 3 m, a 0.9 m corridor y 1.05-1.95 m between x 1.5 and 4.5 m, three cubes in it.
inline GroundMissionScene Figure10Scene() {
  GroundMissionScene scene;
  scene.area_max_W = Eigen::Vector2d(6.0, 3.0);
  scene.fixed_obstacles = {Block(1.5, 0.0, 4.5, 1.05), Block(1.5, 1.95, 4.5, 3.0)};
  scene.movable_obstacles = {Cube(2.2, 1.5), Cube(3.0, 1.5), Cube(3.8, 1.5)};
  scene.robot_p_W = Eigen::Vector2d(0.6, 1.5);
  scene.robot_yaw_rad = 0.0;
  scene.goal_p_W = Eigen::Vector2d(5.4, 1.5);
  return scene;
}

}  // namespace aperture::planning::testing
