#pragma once
// Alg. 3 of paper D (Sec. D.5.2, "Optimizing Grid Map Paths"): a Dijkstra cell path is shortened
// to the cells where the line of sight (OccupancyGrid::LineOfSight) to the last kept cell breaks,
// then every kept cell is turned to point at the next one (Fig. D.7).
#include <Eigen/Core>
#include <vector>

#include "planning/ground_mission/occupancy_grid.h"

namespace aperture::planning {

// A waypoint of the robot base: its centre and its heading (x of the base) in W.
struct GroundWaypoint {
  Eigen::Vector2d p_W = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;
};

// The kept cells of Alg. 3 in order: the first and last cell of `cells` and, in between, each
// cell after which the line of sight from the previously kept cell is lost. A one-cell path
// stays one cell; an empty one stays empty.
std::vector<int> RefineGridPath(const OccupancyGrid& grid, const std::vector<int>& cells);

// Waypoints at the centres of `cells`, each heading to the next, the last one final_yaw_rad (the
// planner: facing the obstacle to grasp or the goal).
std::vector<GroundWaypoint> OrientWaypoints(const OccupancyGrid& grid,
                                            const std::vector<int>& cells, double final_yaw_rad);

}  // namespace aperture::planning
