#pragma once
// Single-source (or multi-source) Dijkstra on an OccupancyGrid, paper D Sec. D.5.2: 8-connected
// moves between free cells, straight steps cost one cell size, diagonal ones sqrt(2) of it (no
// corner check: the obstacles are inflated by the robot radius, far more than a cell). One run
// gives the shortest grid distance from the sources to every cell, hence the paths to all grasp
// locations and the goal at once.
#include <vector>

#include "planning/ground_mission/occupancy_grid.h"

namespace aperture::planning {

struct GridDistances {
  std::vector<double> distance_m;  // per cell; +inf where unreachable or blocked
  std::vector<int> parent;  // per cell: the previous cell of its shortest path, -1 at a source
};

// Distances from the free cells of `sources` (blocked ones are skipped). std::invalid_argument
// for a source index outside the grid.
GridDistances RunGridDijkstra(const OccupancyGrid& grid, const std::vector<int>& sources);

// The cells of the shortest path from a source to `target` (both included); empty when target
// is unreachable.
std::vector<int> ExtractGridPath(const GridDistances& distances, int target);

// Of `candidates`, the reachable cell nearest to the sources (lowest index on ties), -1 if none.
int NearestReachableCell(const GridDistances& distances, const std::vector<int>& candidates);

}  // namespace aperture::planning
