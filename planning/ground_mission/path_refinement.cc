#include "planning/ground_mission/path_refinement.h"

#include <cmath>

namespace aperture::planning {

std::vector<int> RefineGridPath(const OccupancyGrid& grid, const std::vector<int>& cells) {
  if (cells.size() <= 1) return cells;
  std::vector<int> kept{cells.front()};
  for (size_t i = 1; i < cells.size(); ++i) {
    if (!grid.LineOfSight(kept.back(), cells[i])) kept.push_back(cells[i - 1]);
  }
  kept.push_back(cells.back());
  return kept;
}

std::vector<GroundWaypoint> OrientWaypoints(const OccupancyGrid& grid,
                                            const std::vector<int>& cells, double final_yaw_rad) {
  std::vector<GroundWaypoint> waypoints(cells.size());
  for (size_t i = 0; i < cells.size(); ++i) waypoints[i].p_W = grid.CenterOf(cells[i]);
  for (size_t i = 0; i + 1 < cells.size(); ++i) {
    const Eigen::Vector2d d_W = waypoints[i + 1].p_W - waypoints[i].p_W;
    waypoints[i].yaw_rad = std::atan2(d_W.y(), d_W.x());
  }
  if (!waypoints.empty()) waypoints.back().yaw_rad = final_yaw_rad;
  return waypoints;
}

}  // namespace aperture::planning
