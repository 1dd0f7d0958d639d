#pragma once
// A piecewise-straight path in the ground plane parameterised by arc length s [m] from its first
// vertex: the mission path along which the place-location search of paper D Sec. D.5.1 looks
// for places beside the robot (Fig. D.6).
#include <Eigen/Core>
#include <vector>

namespace aperture::planning {

class GroundPolyline {
 public:
  // Appends a vertex (a repeat of the last one adds nothing).
  void Append(const Eigen::Vector2d& p_W);

  double length_m() const { return arc_m_.empty() ? 0.0 : arc_m_.back(); }
  const std::vector<Eigen::Vector2d>& vertices() const { return vertices_; }
  // The point at arc length s_m (clamped to [0, length_m()]); needs a vertex.
  Eigen::Vector2d PointAt(double s_m) const;
  // Unit direction of the piece that starts at or before s_m (the last piece at the end); +x for
  // a single vertex.
  Eigen::Vector2d DirectionAt(double s_m) const;
  // Distance from q_W to the part of the path between arc lengths s_begin_m and s_end_m.
  double DistanceTo(const Eigen::Vector2d& q_W, double s_begin_m, double s_end_m) const;

 private:
  int PieceAt(double s_m) const;

  std::vector<Eigen::Vector2d> vertices_;
  std::vector<double> arc_m_;  // arc length at each vertex
};

}  // namespace aperture::planning
