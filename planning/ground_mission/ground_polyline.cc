#include "planning/ground_mission/ground_polyline.h"

#include <algorithm>
#include <limits>

namespace aperture::planning {

void GroundPolyline::Append(const Eigen::Vector2d& p_W) {
  if (vertices_.empty()) {
    vertices_.push_back(p_W);
    arc_m_.push_back(0.0);
    return;
  }
  const double step_m = (p_W - vertices_.back()).norm();
  if (step_m == 0.0) return;
  vertices_.push_back(p_W);
  arc_m_.push_back(arc_m_.back() + step_m);
}

int GroundPolyline::PieceAt(double s_m) const {
  // The last vertex at or before s_m, capped so that a piece follows it.
  const auto after = std::upper_bound(arc_m_.begin(), arc_m_.end(), s_m);
  const int vertex = static_cast<int>(after - arc_m_.begin()) - 1;
  return std::clamp(vertex, 0, std::max(0, static_cast<int>(vertices_.size()) - 2));
}

Eigen::Vector2d GroundPolyline::PointAt(double s_m) const {
  if (vertices_.size() == 1) return vertices_.front();
  const double s = std::clamp(s_m, 0.0, length_m());
  const int i = PieceAt(s);
  const double t = (s - arc_m_[i]) / (arc_m_[i + 1] - arc_m_[i]);
  return vertices_[i] + std::clamp(t, 0.0, 1.0) * (vertices_[i + 1] - vertices_[i]);
}

Eigen::Vector2d GroundPolyline::DirectionAt(double s_m) const {
  if (vertices_.size() < 2) return Eigen::Vector2d::UnitX();
  const int i = PieceAt(s_m);
  return (vertices_[i + 1] - vertices_[i]).normalized();
}

double GroundPolyline::DistanceTo(const Eigen::Vector2d& q_W, double s_begin_m,
                                  double s_end_m) const {
  double best_m = std::numeric_limits<double>::infinity();
  if (vertices_.empty() || s_end_m < s_begin_m) return best_m;
  const auto distance_to_piece = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((q_W - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return (a + t * ab - q_W).norm();
  };
  const Eigen::Vector2d begin = PointAt(s_begin_m);
  const Eigen::Vector2d end = PointAt(s_end_m);
  if (vertices_.size() == 1) return (begin - q_W).norm();
  const int first = PieceAt(std::clamp(s_begin_m, 0.0, length_m()));
  const int last = PieceAt(std::clamp(s_end_m, 0.0, length_m()));
  for (int i = first; i <= last; ++i) {
    const Eigen::Vector2d a = i == first ? begin : vertices_[i];
    const Eigen::Vector2d b = i == last ? end : vertices_[i + 1];
    best_m = std::min(best_m, distance_to_piece(a, b));
  }
  return best_m;
}

}  // namespace aperture::planning
