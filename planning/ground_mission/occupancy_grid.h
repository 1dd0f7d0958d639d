#pragma once
// The planner's grid map of paper D Sec. D.5: square cells over the field (D.7: 5 cm), each free
// or blocked for the centre of the robot base. Obstacles are entered inflated by the robot
// radius, so a free cell is a collision-free position of the robot centre. Cells are indexed
// row-major: index = row * cols() + col, col along x_W, row along y_W from the field's min corner.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "planning/ground_mission/ground_mission_scene.h"

namespace aperture::planning {

class OccupancyGrid {
 public:
  // Every cell free. std::invalid_argument unless max_W > min_W and cell_size_m > 0.
  OccupancyGrid(const Eigen::Vector2d& min_W, const Eigen::Vector2d& max_W, double cell_size_m);

  int cols() const { return cols_; }
  int rows() const { return rows_; }
  int size() const { return cols_ * rows_; }
  double cell_size_m() const { return cell_size_m_; }
  int Index(int col, int row) const { return row * cols_ + col; }
  int ColOf(int index) const { return index % cols_; }
  int RowOf(int index) const { return index / cols_; }
  Eigen::Vector2d CenterOf(int index) const;
  // The cell holding p_W, std::nullopt outside the grid.
  std::optional<int> CellAt(const Eigen::Vector2d& p_W) const;

  bool blocked(int index) const { return blocked_[static_cast<size_t>(index)] != 0; }
  // Blocks the cells whose centres lie within margin_m of the disc / rectangle / outside the
  // rectangle [min_W + margin_m, max_W - margin_m] (the field border as a wall).
  void BlockDisc(const Eigen::Vector2d& center_W, double radius_m, double margin_m);
  void BlockBox(const GroundBox& box, double margin_m);
  void BlockBorder(double margin_m);

  // Free cells whose centres lie within radius_m of center_W (the grasp locations of D.5,
  // Fig. D.5), in index order.
  std::vector<int> FreeCellsWithin(const Eigen::Vector2d& center_W, double radius_m) const;

  // Line of sight between two cells (Alg. 3): every cell of the Bresenham line from one to the
  // other is free. That line is itself an 8-connected path of max(|dc|, |dr|) steps, min of them
  // diagonal, i.e. of the octile length the Dijkstra search (grid_dijkstra.h) charges, which
  // keeps the planner's lower bounds admissible for refined paths (ground_mission_planner.h).
  bool LineOfSight(int from, int to) const;

 private:
  template <typename DistanceFn>
  void BlockWhere(const Eigen::Vector2d& lo_W, const Eigen::Vector2d& hi_W, DistanceFn distance,
                  double margin_m);

  Eigen::Vector2d min_W_;
  double cell_size_m_;
  int cols_;
  int rows_;
  std::vector<unsigned char> blocked_;
};

}  // namespace aperture::planning
