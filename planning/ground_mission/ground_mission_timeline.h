#pragma once
// Where everything is while the ground robot executes a planned GroundMission open loop (paper D
// Sec. D.6-D.7, no odometry drift): a pure function of the time t_s since the start of the
// execution, timed exactly as the planner's cost model (ground_mission_planner.h, D.7), so that
// duration_s() equals mission.cost_s.
//
// The robot, in order:
// - each leg, as GroundMissionPlanner::MakeLeg counts it: at every waypoint it first turns on
//   the spot to the waypoint's yaw_rad (shortest way, turn_rate_deg_s; the heading before the
//   first waypoint is scene.robot_yaw_rad), then drives the straight piece to the next waypoint
//   (driving_speed_mps); the last waypoint's yaw faces the obstacle or the goal.
// - at the end of a removal leg, "grasp" for remove_time_s / 2: the obstacle moves in a straight
//   line from its place to the robot's centre (and turns to the robot's yaw). It is then lifted
//   onto the robot: its centre is the robot's centre, its yaw the robot's, until it is placed.
// - placing (GroundObstacleRemoval): with backward_m > 0 the robot reverses along the mission
//   path from grasp_s_m to place_s_m without turning ("back", the base is omnidirectional),
//   places, and drives forward to the grasp location again ("drive"): 2 x backward_m / speed,
//   as the planner counts. Otherwise it places when its arc length along the path reaches
//   place_s_m (ahead, on the next leg, at no extra time), stopping there; at a waypoint after
//   turning to the next piece, beside which the place search put it. "place" lasts
//   remove_time_s / 2: the obstacle moves in a straight line from the robot's centre to
//   place_p_W and turns back to its original yaw, where it stays.
// - the last leg ends facing the goal, the mission's end: "done". The cost model counts no
//   delivery time (it is the same for every mission), so there is no "deliver" phase; the
//   simulator may append one.
// `carried` names the obstacle in the gripper from the start of its grasp to the end of its
// place (it rides with the robot in between).
//
// Open loop: the robot executes the legs' turn and drive commands from its true start pose,
// scene.robot_p_W, while the planner's waypoints are cell centres (the first within half a cell
// diagonal of it). The robot's whole path is therefore the planned one shifted by
// start_offset_W() = scene.robot_p_W - first waypoint; the gripper places the obstacles at
// their planned place_p_W.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "planning/ground_mission/ground_mission_planner.h"

namespace aperture::planning {

// Everything at one time t_s (0 = start of execution).
struct GroundRobotSample {
  Eigen::Vector2d robot_p_W = Eigen::Vector2d::Zero();
  double robot_yaw_rad = 0.0;                // in [-pi, pi]
  std::vector<Eigen::Vector2d> movable_p_W;  // every movable obstacle's centre, scene's order
  std::vector<double> movable_yaw_rad;
  int carried = -1;      // the obstacle in the gripper (grasp to place), -1 none
  std::string activity;  // "turn", "drive", "grasp", "back", "place" or "done"
  int leg = 0;           // index into mission.legs
};

// When a removal's obstacle is in the gripper (times from the start of execution).
struct GroundRemovalTimes {
  int obstacle = -1;
  double grasp_start_s = 0.0;
  double grasp_end_s = 0.0;  // from here it rides with the robot
  double place_start_s = 0.0;
  double place_end_s = 0.0;  // from here it lies at place_p_W
};

// One straight drive of the robot (forward or backward), a segment the robot executes open loop
// on its wheel odometry (D.6); times from the start of execution.
struct GroundDriveSegment {
  double start_s = 0.0;
  double end_s = 0.0;
};

class GroundMissionTimeline {
 public:
  // `mission` planned by GroundMissionPlanner(scene, params). std::invalid_argument when the
  // mission is not solved or does not fit the scene (obstacle indices, one removal per leg but
  // the last, places along the path), or for non-positive speed or turn rate.
  GroundMissionTimeline(const GroundMission& mission, const GroundMissionScene& scene,
                        const GroundMissionParams& params);

  double duration_s() const { return duration_s_; }
  // t_s clamped to [0, duration_s()]; std::invalid_argument for NaN.
  GroundRobotSample Sample(double t_s) const;

  const std::vector<GroundRemovalTimes>& removal_times() const { return removal_times_; }
  const Eigen::Vector2d& start_offset_W() const { return start_offset_W_; }
  // Every "drive" and "back" phase in order (a straight piece split at a place stop is two).
  std::vector<GroundDriveSegment> DriveSegments() const;

 private:
  // One motion of the robot: a turn on the spot, a straight drive along the mission path
  // (forward or backward) or a stop to grasp or place.
  struct Phase {
    const char* activity = "";
    int leg = 0;
    double start_s = 0.0;
    double duration_s = 0.0;
    double from_s_m = 0.0;  // arc length along the mission path at the start
    double to_s_m = 0.0;    // and at the end (equal unless driving)
    double from_yaw_rad = 0.0;
    double to_yaw_rad = 0.0;  // turning the shortest way (equal unless turning)
  };
  GroundMissionScene scene_;
  std::vector<GroundObstacleRemoval> removals_;
  GroundPolyline path_;
  Eigen::Vector2d start_offset_W_ = Eigen::Vector2d::Zero();
  std::vector<Phase> phases_;
  std::vector<GroundRemovalTimes> removal_times_;
  double duration_s_ = 0.0;
  double final_yaw_rad_ = 0.0;
  int last_leg_ = 0;
};

}  // namespace aperture::planning
