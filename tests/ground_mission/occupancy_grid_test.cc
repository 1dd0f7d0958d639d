// The grid map, Dijkstra and Alg. 3 of paper D Sec. D.5.2 against closed-form cases.
#include "planning/ground_mission/occupancy_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "planning/ground_mission/grid_dijkstra.h"
#include "planning/ground_mission/ground_polyline.h"
#include "planning/ground_mission/path_refinement.h"

namespace aperture::planning {
namespace {

constexpr double kCell_m = 0.05;

OccupancyGrid EmptyGrid() {
  return OccupancyGrid(Eigen::Vector2d::Zero(), Eigen::Vector2d(2.0, 1.0), kCell_m);
}

TEST(OccupancyGridTest, InflatesABoxByTheMargin) {
  OccupancyGrid grid = EmptyGrid();
  const GroundBox box{Eigen::Vector2d(1.0, 0.5), Eigen::Vector2d(0.2, 0.1), 0.3};
  grid.BlockBox(box, 0.25);
  for (int index = 0; index < grid.size(); ++index) {
    EXPECT_EQ(grid.blocked(index), DistanceToBox(box, grid.CenterOf(index)) <= 0.25) << index;
  }
  // The rotated box: a corner at distance 0, a point beyond its long side.
  const Eigen::Vector2d along(std::cos(0.3), std::sin(0.3));
  EXPECT_NEAR(DistanceToBox(box, box.p_W + 0.1 * along), 0.0, 1e-12);
  EXPECT_NEAR(DistanceToBox(box, box.p_W + 0.4 * along), 0.3, 1e-12);
}

TEST(OccupancyGridTest, DijkstraOnAnEmptyGridGivesTheOctileDistance) {
  const OccupancyGrid grid = EmptyGrid();
  const int source = grid.Index(3, 4);
  const GridDistances distances = RunGridDijkstra(grid, {source});
  for (const int target :
       {grid.Index(3, 4), grid.Index(30, 4), grid.Index(12, 19), grid.Index(39, 0)}) {
    const int dc = std::abs(grid.ColOf(target) - 3);
    const int dr = std::abs(grid.RowOf(target) - 4);
    const double octile_m = kCell_m * (std::max(dc, dr) + (std::sqrt(2.0) - 1) * std::min(dc, dr));
    EXPECT_NEAR(distances.distance_m[static_cast<size_t>(target)], octile_m, 1e-9);
    const std::vector<int> path = ExtractGridPath(distances, target);
    ASSERT_FALSE(path.empty());
    EXPECT_EQ(path.front(), source);
    EXPECT_EQ(path.back(), target);
    // Alg. 3 on free space: the straight line from the first to the last cell.
    const std::vector<int> refined = RefineGridPath(grid, path);
    EXPECT_EQ(refined.size(), path.size() == 1 ? 1u : 2u);
  }
}

TEST(OccupancyGridTest, RefinementKeepsTheCornerOfAWall) {
  // A wall from the bottom up to y = 0.6 m at x = 1 m: the path from the lower left to the lower
  // right goes over it; Alg. 3 keeps start, the cells at the wall's top and the end, and every
  // kept piece has line of sight.
  OccupancyGrid grid = EmptyGrid();
  grid.BlockBox({Eigen::Vector2d(1.0, 0.3), Eigen::Vector2d(0.1, 0.6), 0.0}, 0.1);
  const int start = *grid.CellAt(Eigen::Vector2d(0.3, 0.1));
  const int goal = *grid.CellAt(Eigen::Vector2d(1.7, 0.1));
  EXPECT_FALSE(grid.LineOfSight(start, goal));
  const GridDistances distances = RunGridDijkstra(grid, {start});
  const std::vector<int> path = ExtractGridPath(distances, goal);
  const std::vector<int> refined = RefineGridPath(grid, path);
  ASSERT_GE(refined.size(), 3u);
  EXPECT_LE(refined.size(), 5u);
  double refined_m = 0.0;
  for (size_t i = 0; i + 1 < refined.size(); ++i) {
    EXPECT_TRUE(grid.LineOfSight(refined[i], refined[i + 1]));
    refined_m += (grid.CenterOf(refined[i + 1]) - grid.CenterOf(refined[i])).norm();
  }
  // Shorter than the grid path, not shorter than over the inflated wall's top corners.
  const double over_corners_m = (Eigen::Vector2d(0.9, 0.7) - grid.CenterOf(start)).norm() + 0.2 +
                                (grid.CenterOf(goal) - Eigen::Vector2d(1.1, 0.7)).norm();
  EXPECT_LT(refined_m, distances.distance_m[static_cast<size_t>(goal)]);
  EXPECT_GT(refined_m, over_corners_m - 2 * kCell_m);
  const std::vector<GroundWaypoint> waypoints = OrientWaypoints(grid, refined, 0.5);
  const Eigen::Vector2d first = waypoints[1].p_W - waypoints[0].p_W;
  EXPECT_NEAR(waypoints[0].yaw_rad, std::atan2(first.y(), first.x()), 1e-12);
  EXPECT_EQ(waypoints.back().yaw_rad, 0.5);
}

TEST(OccupancyGridTest, PolylineMeasuresArcLength) {
  GroundPolyline path;
  path.Append(Eigen::Vector2d(0, 0));
  path.Append(Eigen::Vector2d(3, 0));
  path.Append(Eigen::Vector2d(3, 0));  // repeated vertex adds nothing
  path.Append(Eigen::Vector2d(3, 4));
  EXPECT_DOUBLE_EQ(path.length_m(), 7.0);
  EXPECT_TRUE(path.PointAt(5.0).isApprox(Eigen::Vector2d(3, 2)));
  EXPECT_TRUE(path.DirectionAt(3.0).isApprox(Eigen::Vector2d(0, 1)));
  EXPECT_TRUE(path.DirectionAt(1.0).isApprox(Eigen::Vector2d(1, 0)));
  // (4, 1) is 1 m from the second piece, sqrt(2) m from the first piece's end.
  EXPECT_NEAR(path.DistanceTo(Eigen::Vector2d(4, 1), 0.0, 7.0), 1.0, 1e-12);
  EXPECT_NEAR(path.DistanceTo(Eigen::Vector2d(4, 1), 0.0, 3.0), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(path.DistanceTo(Eigen::Vector2d(4, 1), 5.0, 7.0), std::sqrt(2.0), 1e-12);
}

}  // namespace
}  // namespace aperture::planning
