#include "planning/mono_nav/flown_trail.h"

#include <stdexcept>
#include <string>

namespace aperture::planning {

FlownTrail::FlownTrail(double spacing_m) : spacing_m_(spacing_m) {
  if (!(spacing_m > 0.0)) {
    throw std::invalid_argument("FlownTrail: spacing_m must be > 0, got " +
                                std::to_string(spacing_m));
  }
}

void FlownTrail::Add(const Eigen::Vector3d& p_W) {
  if (points_W_.empty() || (p_W - points_W_.back()).norm() >= spacing_m_) points_W_.push_back(p_W);
}

std::vector<Eigen::Vector3d> FlownTrail::BackOffPath(const Eigen::Vector3d& p_W,
                                                     double length_m) const {
  std::vector<Eigen::Vector3d> path_W{p_W};
  double length = 0.0;
  for (auto it = points_W_.rbegin(); it != points_W_.rend() && length < length_m; ++it) {
    length += (*it - path_W.back()).norm();
    path_W.push_back(*it);
  }
  return path_W;
}

void FlownTrail::Retrace(const std::vector<Eigen::Vector3d>& path_W) {
  // path_W holds the start and then the latest trail points: keep its end, drop those after it.
  if (path_W.size() < 2) return;
  const size_t used = path_W.size() - 1;
  if (used > points_W_.size()) {
    throw std::invalid_argument("FlownTrail::Retrace: the path is longer than the trail");
  }
  points_W_.resize(points_W_.size() - used + 1);
}

double PolylineLength(const std::vector<Eigen::Vector3d>& points_W) {
  double length = 0.0;
  for (size_t k = 1; k < points_W.size(); ++k) length += (points_W[k] - points_W[k - 1]).norm();
  return length;
}

}  // namespace aperture::planning
