#include "planning/ground_mission/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace aperture::planning {

OccupancyGrid::OccupancyGrid(const Eigen::Vector2d& min_W, const Eigen::Vector2d& max_W,
                             double cell_size_m)
    : min_W_(min_W), cell_size_m_(cell_size_m) {
  if (!(cell_size_m > 0.0) || !(max_W.x() > min_W.x()) || !(max_W.y() > min_W.y())) {
    throw std::invalid_argument(
        "OccupancyGrid: needs a positive cell size (got " + std::to_string(cell_size_m) +
        " m) and an area whose max corner lies above its min corner in x and y");
  }
  cols_ = static_cast<int>(std::ceil((max_W.x() - min_W.x()) / cell_size_m - 1e-9));
  rows_ = static_cast<int>(std::ceil((max_W.y() - min_W.y()) / cell_size_m - 1e-9));
  blocked_.assign(static_cast<size_t>(cols_) * static_cast<size_t>(rows_), 0);
}

Eigen::Vector2d OccupancyGrid::CenterOf(int index) const {
  return min_W_ + cell_size_m_ * Eigen::Vector2d(ColOf(index) + 0.5, RowOf(index) + 0.5);
}

std::optional<int> OccupancyGrid::CellAt(const Eigen::Vector2d& p_W) const {
  const Eigen::Vector2d cell = (p_W - min_W_) / cell_size_m_;
  const int col = static_cast<int>(std::floor(cell.x()));
  const int row = static_cast<int>(std::floor(cell.y()));
  if (col < 0 || row < 0 || col >= cols_ || row >= rows_) return std::nullopt;
  return Index(col, row);
}

template <typename DistanceFn>
void OccupancyGrid::BlockWhere(const Eigen::Vector2d& lo_W, const Eigen::Vector2d& hi_W,
                               DistanceFn distance, double margin_m) {
  const auto clamp_col = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - min_W_.x()) / cell_size_m_)), 0, cols_ - 1);
  };
  const auto clamp_row = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - min_W_.y()) / cell_size_m_)), 0, rows_ - 1);
  };
  for (int row = clamp_row(lo_W.y() - margin_m); row <= clamp_row(hi_W.y() + margin_m); ++row) {
    for (int col = clamp_col(lo_W.x() - margin_m); col <= clamp_col(hi_W.x() + margin_m); ++col) {
      const int index = Index(col, row);
      if (distance(CenterOf(index)) <= margin_m) blocked_[static_cast<size_t>(index)] = 1;
    }
  }
}

void OccupancyGrid::BlockDisc(const Eigen::Vector2d& center_W, double radius_m, double margin_m) {
  const Eigen::Vector2d extent = Eigen::Vector2d::Constant(radius_m);
  BlockWhere(
      center_W - extent, center_W + extent,
      [&](const Eigen::Vector2d& q_W) { return std::max(0.0, (q_W - center_W).norm() - radius_m); },
      margin_m);
}

void OccupancyGrid::BlockBox(const GroundBox& box, double margin_m) {
  const Eigen::Vector2d extent = Eigen::Vector2d::Constant(CircumscribedRadius(box));
  BlockWhere(
      box.p_W - extent, box.p_W + extent,
      [&](const Eigen::Vector2d& q_W) { return DistanceToBox(box, q_W); }, margin_m);
}

void OccupancyGrid::BlockBorder(double margin_m) {
  const Eigen::Vector2d max_W = min_W_ + cell_size_m_ * Eigen::Vector2d(cols_, rows_);
  for (int index = 0; index < size(); ++index) {
    const Eigen::Vector2d c = CenterOf(index);
    const double inside_m = std::min((c - min_W_).minCoeff(), (max_W - c).minCoeff());
    if (inside_m < margin_m) blocked_[static_cast<size_t>(index)] = 1;
  }
}

std::vector<int> OccupancyGrid::FreeCellsWithin(const Eigen::Vector2d& center_W,
                                                double radius_m) const {
  std::vector<int> cells;
  const auto cell_range = [&](double lo, double hi, double origin, int count) {
    return std::make_pair(
        std::max(0, static_cast<int>(std::floor((lo - origin) / cell_size_m_))),
        std::min(count - 1, static_cast<int>(std::floor((hi - origin) / cell_size_m_))));
  };
  const auto [row_lo, row_hi] =
      cell_range(center_W.y() - radius_m, center_W.y() + radius_m, min_W_.y(), rows_);
  const auto [col_lo, col_hi] =
      cell_range(center_W.x() - radius_m, center_W.x() + radius_m, min_W_.x(), cols_);
  for (int row = row_lo; row <= row_hi; ++row) {
    for (int col = col_lo; col <= col_hi; ++col) {
      const int index = Index(col, row);
      if (!blocked(index) && (CenterOf(index) - center_W).norm() <= radius_m) {
        cells.push_back(index);
      }
    }
  }
  return cells;
}

bool OccupancyGrid::LineOfSight(int from, int to) const {
  int col = ColOf(from);
  int row = RowOf(from);
  const int col_end = ColOf(to);
  const int row_end = RowOf(to);
  const int dc = std::abs(col_end - col);
  const int dr = -std::abs(row_end - row);
  const int step_col = col < col_end ? 1 : -1;
  const int step_row = row < row_end ? 1 : -1;
  int error = dc + dr;  // Bresenham's all-octant form
  while (true) {
    if (blocked(Index(col, row))) return false;
    if (col == col_end && row == row_end) return true;
    const int twice = 2 * error;
    if (twice >= dr) {
      error += dr;
      col += step_col;
    }
    if (twice <= dc) {
      error += dc;
      row += step_row;
    }
  }
}

}  // namespace aperture::planning
