#pragma once
// Time-optimal missions of a ground robot among movable obstacles, paper D (seed 001) Sec. D.5:
// the robot (an omnidirectional base with a gripper, D.3.2) drives to the goal and may on its
// way remove movable obstacles, each by driving to one of its grasp locations (Fig. D.5),
// grasping it and placing it beside its path (D.5.1). A mission is the order of the removals
// and a leg (a path) to each grasp location and finally to the goal, where the first-aid kit is
// delivered from the grasp circle around the goal (D.6).
//
// Map (D.5): an OccupancyGrid whose cells are blocked within robot_radius_m of the field border,
// the fixed obstacles, the goal footprint and the movable obstacles still in place (each as its
// circumscribed disc, whatever its yaw). Grasp locations of an obstacle: the free cells within
// grasp_radius_m of its centre; the leg to it ends at the nearest one (single-source Dijkstra,
// grid_dijkstra.h) and is refined by Alg. 3 (path_refinement.h). Waypoints are cell centres:
// the first one lies within half a cell diagonal of the robot's pose.
//
// Cost (D.7): mission time = driven length / driving_speed_mps + heading changes / turn_rate
// (the robot faces along each refined piece and, at the end of a leg, the obstacle or the goal;
// D.5.2 "update orientation such that it points to next cell") + remove_time_s per removal
// + 2 * backward distance / driving_speed_mps for obstacles carried back to a place (the base is
// omnidirectional: it reverses along its path without turning).
//
// Alg. 2 (Plan): a priority queue of partial missions ordered by a lower bound: their exact cost
// so far (without the backward driving, only known once the mission is complete) plus a lower
// bound on the time from their last grasp location to the goal: the grid distance to the goal's
// grasp circle with no movable obstacle present (one Dijkstra from the goal), divided by the
// largest octile/Euclidean length ratio sqrt(4 - 2 sqrt 2) (a refined piece is a Bresenham line
// whose grid length is its octile length, see OccupancyGrid::LineOfSight) and by the speed.
// Popping a partial mission enters its remaining obstacles into the map, runs one Dijkstra from
// its stop and pushes a child per reachable obstacle whose bound is below the best complete
// cost; when the goal is reachable the completed mission is refined (place search, D.5.1) and
// kept if cheaper. The search stops when the queue's least bound is no longer below the best
// cost, so the result is the cheapest of all orders of all subsets of the movable obstacles,
// each evaluated by the same legs and place search (PlanExhaustively checks it).
//
// Place search (D.5.1, Fig. D.6): the removed obstacle is placed grasp_radius_m to the left or
// right of the robot's path, first at the grasp location and forward along the path up to the
// next grasp location (or the goal's; no extra time), else backward along the path driven so far,
// nearest first (extra time for the backward driving). A place is feasible when the obstacle's
// disc lies inside the field, off the fixed obstacles, the obstacles still in place and those
// already placed, and off the goal footprint, and when that disc grown by the robot radius keeps
// clear of the rest of the path from the place on (and, when carried back, already placed
// obstacles keep clear of the stretch driven twice). A mission without a feasible place for one
// of its removals is infeasible.
#include <Eigen/Core>
#include <iosfwd>
#include <limits>
#include <optional>
#include <vector>

#include "planning/ground_mission/grid_dijkstra.h"
#include "planning/ground_mission/ground_mission_scene.h"
#include "planning/ground_mission/ground_polyline.h"
#include "planning/ground_mission/occupancy_grid.h"
#include "planning/ground_mission/path_refinement.h"

namespace aperture::planning {

struct GroundMissionParams {
  double cell_size_m = 0.05;  // D.7: "a cell size of 5 cm"
  // The KUKA youBot base of D.3.2 (0.58 x 0.38 m, sim TagsSceneParams::robot_size_m): half its
  // diagonal, 0.347 m, so the inflated obstacles cover any heading of the base.
  double robot_radius_m = 0.35;
  // Base centre to the grasped object (Fig. D.5): the youBot arm reaches ~0.5 m ahead of the
  // base centre. Must exceed robot_radius_m + a movable obstacle's circumscribed radius (0.127 m
  // for the tags scenario's 18 cm cubes), or the obstacle would hide its own grasp circle.
  double grasp_radius_m = 0.5;
  double driving_speed_mps = 0.2;  // D.7
  double turn_rate_deg_s = 30.0;   // D.7
  double remove_time_s = 15.0;     // D.7: "15 s for grasping and placing an obstacle"
};

// One leg: from where the robot stands to a grasp location (or to the goal's grasp circle).
struct GroundMissionLeg {
  int target = -1;  // index of the movable obstacle to grasp, -1 for the goal
  // Alg. 3 waypoints: the first is the previous stop, the last faces the obstacle or the goal.
  std::vector<GroundWaypoint> waypoints;
  double length_m = 0.0;
  double turn_rad = 0.0;  // sum of the absolute heading changes, from the heading at the start
  double time_s = 0.0;    // length_m / speed + turn_rad / turn rate
};

struct GroundObstacleRemoval {
  int obstacle = -1;
  Eigen::Vector2d grasp_p_W = Eigen::Vector2d::Zero();           // where the robot grasps it
  Eigen::Vector2d place_p_W = Eigen::Vector2d::Zero();           // where the obstacle is put down
  Eigen::Vector2d robot_at_place_p_W = Eigen::Vector2d::Zero();  // the robot while placing it
  double grasp_s_m = 0.0;   // arc length of the grasp location along the mission path
  double place_s_m = 0.0;   // arc length of the robot's place position along that path
  double backward_m = 0.0;  // carried back (grasp_s_m - place_s_m), 0 when placed ahead
};

enum class GroundMissionStatus { kSolved, kNoMission };

struct GroundMission {
  GroundMissionStatus status = GroundMissionStatus::kNoMission;
  std::vector<GroundMissionLeg> legs;  // one per removal, in order, then the leg to the goal
  std::vector<GroundObstacleRemoval> removals;
  double cost_s = std::numeric_limits<double>::infinity();  // mission time
  double drive_s = 0.0;                                     // forward driving along the legs
  double turn_s = 0.0;                                      // turning on the spot
  double remove_s = 0.0;                                    // grasping and placing
  double backward_s = 0.0;    // carrying obstacles back and returning (2 x backward_m / speed)
  int missions_expanded = 0;  // partial missions popped (Plan) or visited (PlanExhaustively)
  double solve_time_s = 0.0;

  bool solved() const { return status == GroundMissionStatus::kSolved; }
  std::vector<int> Order() const;  // the removed obstacles in order
  double path_length_m() const;    // sum of the legs' lengths
};

std::ostream& operator<<(std::ostream& out, const GroundMission& mission);

// The mission path of D.5.1: the legs' waypoints in order as one polyline from the start to the
// goal (the place search and the execution timeline measure arc lengths along it), and the arc
// length at the end of each leg (a removal's grasp_s_m).
struct GroundMissionPath {
  GroundPolyline polyline;
  std::vector<double> leg_end_s_m;
};
GroundMissionPath BuildMissionPath(const std::vector<GroundMissionLeg>& legs);

class GroundMissionPlanner {
 public:
  // std::invalid_argument naming the value for inconsistent parameters (non-positive sizes,
  // speeds or times, a grasp radius not beyond robot radius + an obstacle's or the goal's
  // radius) or a scene whose robot or goal lies outside the field or whose robot collides.
  GroundMissionPlanner(const GroundMissionScene& scene, const GroundMissionParams& params = {});

  // Alg. 2: the time-optimal mission, status kNoMission when no order reaches the goal.
  GroundMission Plan() const;
  // The reference: every order of every subset of the movable obstacles evaluated (no bound,
  // no pruning); the cheapest, lowest order first on ties of cost. Exponential: small scenes.
  GroundMission PlanExhaustively() const;
  // The mission that removes `order` (obstacle indices) in that order, then drives to the goal;
  // kNoMission when a leg or a place does not exist.
  GroundMission EvaluateOrder(const std::vector<int>& order) const;

  // The map without movable obstacles (border, fixed obstacles, goal footprint inflated).
  const OccupancyGrid& fixed_grid() const { return fixed_grid_; }
  const GroundMissionScene& scene() const { return scene_; }
  const GroundMissionParams& params() const { return params_; }

 private:
  struct Stop {
    int cell = -1;
    double yaw_rad = 0.0;
  };
  struct Partial {
    std::vector<int> order;
    std::vector<GroundMissionLeg> legs;
    Stop stop;
    double cost_s = 0.0;   // legs and removals so far
    double bound_s = 0.0;  // cost_s + lower bound to the goal
  };
  struct Expansion {
    std::vector<std::optional<GroundMissionLeg>> to_obstacle;  // per movable obstacle
    std::optional<GroundMissionLeg> to_goal;
  };

  OccupancyGrid MapWithout(const std::vector<int>& removed) const;
  Expansion Expand(const Partial& partial) const;
  std::optional<GroundMissionLeg> MakeLeg(const OccupancyGrid& map, const GridDistances& distances,
                                          const Stop& from, int target) const;
  Partial Extend(const Partial& partial, const GroundMissionLeg& leg) const;
  // D.5.1 on a complete mission (legs end at the goal): places and the exact cost.
  GroundMission Complete(const Partial& partial, const GroundMissionLeg& to_goal) const;
  double LowerBoundToGoal_s(int cell) const;
  Partial Start() const;

  GroundMissionScene scene_;
  GroundMissionParams params_;
  OccupancyGrid fixed_grid_;
  std::vector<double> goal_distance_fixed_m_;  // grid distance to the goal's circle, fixed map
};

}  // namespace aperture::planning
