#pragma once
// Place positions of removed obstacles, paper D Sec. D.5.1 and Fig. D.6: the obstacle is put
// down `lateral_m` to the left or right of the robot's path (the gripper's reach beside the
// base), at the first feasible arc length from the grasp location forward up to the next grasp
// location, else at the nearest one backward along the path driven so far.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "planning/ground_mission/ground_mission_scene.h"
#include "planning/ground_mission/ground_polyline.h"

namespace aperture::planning {

// An obstacle's footprint as a disc (its circumscribed circle).
struct PlacedDisc {
  Eigen::Vector2d p_W = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
};

struct PlaceSearchContext {
  const GroundMissionScene* scene = nullptr;  // field, fixed obstacles, goal footprint
  const GroundPolyline* path = nullptr;       // the whole mission path, start to goal
  double robot_radius_m = 0.0;
  double lateral_m = 0.0;            // place offset from the path (the grasp radius)
  double step_m = 0.0;               // arc-length spacing of the candidates (the grid cell size)
  std::vector<PlacedDisc> in_place;  // movable obstacles not removed yet
  std::vector<PlacedDisc> placed;    // removed earlier in the mission
};

struct PlaceLocation {
  Eigen::Vector2d p_W = Eigen::Vector2d::Zero();  // the obstacle's centre once placed
  double robot_s_m = 0.0;                         // the robot's arc length while placing
};

// The place of an obstacle of footprint radius radius_m grasped at arc length grasp_s_m, the
// forward search ending at forward_end_s_m; std::nullopt when neither direction has one.
// Feasible: the disc inside the field, clear of the fixed obstacles, the goal footprint, the
// in_place and placed discs; grown by the robot radius, clear of the path from the robot's
// place position to the end; for a backward place, every placed disc grown by the robot radius
// clear of the stretch driven twice (robot place position to grasp location).
std::optional<PlaceLocation> FindPlaceLocation(const PlaceSearchContext& context, double radius_m,
                                               double grasp_s_m, double forward_end_s_m);

}  // namespace aperture::planning
