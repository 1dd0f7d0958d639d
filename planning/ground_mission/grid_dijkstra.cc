#include "planning/ground_mission/grid_dijkstra.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

namespace aperture::planning {

GridDistances RunGridDijkstra(const OccupancyGrid& grid, const std::vector<int>& sources) {
  const double inf = std::numeric_limits<double>::infinity();
  GridDistances out;
  out.distance_m.assign(static_cast<size_t>(grid.size()), inf);
  out.parent.assign(static_cast<size_t>(grid.size()), -1);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  for (const int source : sources) {
    if (source < 0 || source >= grid.size()) {
      throw std::invalid_argument("RunGridDijkstra: source cell " + std::to_string(source) +
                                  " lies outside the " + std::to_string(grid.size()) +
                                  "-cell grid");
    }
    if (grid.blocked(source)) continue;
    out.distance_m[static_cast<size_t>(source)] = 0.0;
    open.emplace(0.0, source);
  }
  const double straight_m = grid.cell_size_m();
  const double diagonal_m = std::sqrt(2.0) * grid.cell_size_m();
  while (!open.empty()) {
    const auto [distance_m, cell] = open.top();
    open.pop();
    if (distance_m > out.distance_m[static_cast<size_t>(cell)]) continue;  // stale entry
    const int col = grid.ColOf(cell);
    const int row = grid.RowOf(cell);
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        if (dc == 0 && dr == 0) continue;
        const int c = col + dc;
        const int r = row + dr;
        if (c < 0 || r < 0 || c >= grid.cols() || r >= grid.rows()) continue;
        const int next = grid.Index(c, r);
        if (grid.blocked(next)) continue;
        const double through_m = distance_m + (dc != 0 && dr != 0 ? diagonal_m : straight_m);
        if (through_m < out.distance_m[static_cast<size_t>(next)]) {
          out.distance_m[static_cast<size_t>(next)] = through_m;
          out.parent[static_cast<size_t>(next)] = cell;
          open.emplace(through_m, next);
        }
      }
    }
  }
  return out;
}

std::vector<int> ExtractGridPath(const GridDistances& distances, int target) {
  std::vector<int> path;
  if (target < 0 || !std::isfinite(distances.distance_m[static_cast<size_t>(target)])) return path;
  for (int cell = target; cell >= 0; cell = distances.parent[static_cast<size_t>(cell)]) {
    path.push_back(cell);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

int NearestReachableCell(const GridDistances& distances, const std::vector<int>& candidates) {
  int best = -1;
  double best_m = std::numeric_limits<double>::infinity();
  for (const int cell : candidates) {
    const double d_m = distances.distance_m[static_cast<size_t>(cell)];
    if (d_m < best_m || (d_m == best_m && best >= 0 && cell < best)) {
      best_m = d_m;
      best = cell;
    }
  }
  return std::isfinite(best_m) ? best : -1;
}

}  // namespace aperture::planning
