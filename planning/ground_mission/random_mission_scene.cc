#include "planning/ground_mission/random_mission_scene.h"

#include <random>
#include <stdexcept>
#include <string>

#include "control/constants.h"

namespace aperture::planning {

GroundMissionScene SlalomField() {
  GroundMissionScene field;
  field.area_min_W = Eigen::Vector2d::Zero();
  field.area_max_W = Eigen::Vector2d(4.0, 6.0);
  field.fixed_obstacles = {{Eigen::Vector2d(1.3, 2.0), Eigen::Vector2d(2.6, 0.3), 0.0},
                           {Eigen::Vector2d(2.7, 4.0), Eigen::Vector2d(2.6, 0.3), 0.0}};
  field.robot_p_W = Eigen::Vector2d(0.6, 0.6);
  field.robot_yaw_rad = control::kPi / 2;
  field.goal_p_W = Eigen::Vector2d(3.4, 5.4);
  return field;
}

GroundMissionScene PassageField() {
  GroundMissionScene field;
  field.area_min_W = Eigen::Vector2d::Zero();
  field.area_max_W = Eigen::Vector2d(4.0, 3.0);
  field.fixed_obstacles = {{Eigen::Vector2d(2.0, 0.8), Eigen::Vector2d(0.3, 1.6), 0.0}};
  field.robot_p_W = Eigen::Vector2d(0.6, 0.6);
  field.robot_yaw_rad = 0.0;
  field.goal_p_W = Eigen::Vector2d(3.4, 0.6);
  return field;
}

std::pair<Eigen::Vector2d, Eigen::Vector2d> PassageRegion() {
  return {Eigen::Vector2d(1.2, 1.4), Eigen::Vector2d(2.8, 3.0)};
}

GroundMissionScene RandomMissionScene(const RandomMissionSceneParams& params, std::uint64_t seed) {
  GroundMissionScene scene = params.field;
  scene.movable_obstacles.clear();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double radius_m = params.movable_size_m.norm() / 2;
  const bool in_region = (params.region_min_W.array() <= params.region_max_W.array()).all();
  const Eigen::Vector2d min_W = in_region ? params.region_min_W : scene.area_min_W;
  const Eigen::Vector2d extent_W = (in_region ? params.region_max_W : scene.area_max_W) - min_W;
  for (int draw = 0;
       draw < 10000 && static_cast<int>(scene.movable_obstacles.size()) < params.movable_obstacles;
       ++draw) {
    GroundBox box;
    box.size_m = params.movable_size_m;
    box.p_W = min_W + Eigen::Vector2d(unit(rng), unit(rng)).cwiseProduct(extent_W);
    box.yaw_rad = (2.0 * unit(rng) - 1.0) * control::kPi;
    const double keep_m = radius_m + params.clearance_m;
    bool free = ((box.p_W - scene.area_min_W).array() >= keep_m).all() &&
                ((scene.area_max_W - box.p_W).array() >= keep_m).all() &&
                (box.p_W - scene.goal_p_W).norm() >= keep_m + scene.goal_radius_m &&
                (box.p_W - scene.robot_p_W).norm() >= keep_m + params.robot_radius_m;
    for (const GroundBox& fixed : scene.fixed_obstacles) {
      free = free && DistanceToBox(fixed, box.p_W) >= keep_m;
    }
    for (const GroundBox& other : scene.movable_obstacles) {
      free = free && (box.p_W - other.p_W).norm() >= keep_m + radius_m;
    }
    if (free) scene.movable_obstacles.push_back(box);
  }
  if (static_cast<int>(scene.movable_obstacles.size()) < params.movable_obstacles) {
    throw std::runtime_error("RandomMissionScene: placed only " +
                             std::to_string(scene.movable_obstacles.size()) + " of " +
                             std::to_string(params.movable_obstacles) +
                             " movable obstacles in 10000 draws; use fewer or a larger field");
  }
  return scene;
}

}  // namespace aperture::planning
