#pragma once
// What the ground-robot mission planner (ground_mission_planner.h) is told of the field, paper D
// (seed 001) Sec. D.4-D.5: the area, the fixed obstacles (only avoided), the movable obstacles
// (the robot may grasp and place them), the robot's pose and the goal (the victim the first-aid
// kit is delivered to). Everything lies in the ground plane of the map frame W (x, y in m, yaw
// about z_W in rad). A plain description: the `tags` scenario fills it from its objects or its
// tag map (experiments/tags/tags_mission_scene.h), tests and benches write it directly.
#include <Eigen/Core>
#include <vector>

namespace aperture::planning {

// A rectangular footprint centred at p_W, its size_m.x() side along the direction yaw_rad.
struct GroundBox {
  Eigen::Vector2d p_W = Eigen::Vector2d::Zero();
  Eigen::Vector2d size_m = Eigen::Vector2d(0.5, 0.5);
  double yaw_rad = 0.0;
};

// Euclidean distance from q_W to the rectangle (0 inside it).
double DistanceToBox(const GroundBox& box, const Eigen::Vector2d& q_W);
// Whether the two rectangles share interior points (separating-axis test on their 4 edge
// directions; touching edges do not overlap).
bool BoxesOverlap(const GroundBox& a, const GroundBox& b);
// Radius of the circle around p_W that holds the rectangle (half its diagonal): a movable
// obstacle's footprint whatever yaw it is placed with.
double CircumscribedRadius(const GroundBox& box);

struct GroundMissionScene {
  // The field rectangle [area_min_W, area_max_W]; its border is a wall.
  Eigen::Vector2d area_min_W = Eigen::Vector2d::Zero();
  Eigen::Vector2d area_max_W = Eigen::Vector2d(4.0, 6.0);
  std::vector<GroundBox> fixed_obstacles;
  std::vector<GroundBox> movable_obstacles;             // a mission refers to them by index
  Eigen::Vector2d robot_p_W = Eigen::Vector2d::Zero();  // centre of the robot base
  double robot_yaw_rad = 0.0;                           // the gripper's side, x of the base
  Eigen::Vector2d goal_p_W = Eigen::Vector2d::Zero();
  // The victim's footprint around goal_p_W: the robot does not drive over it and no obstacle is
  // placed on it. The kit is delivered from the grasp circle around goal_p_W (D.6).
  double goal_radius_m = 0.1;
};

}  // namespace aperture::planning
