#include "planning/ground_mission/ground_mission_scene.h"

#include <cmath>

namespace aperture::planning {

double DistanceToBox(const GroundBox& box, const Eigen::Vector2d& q_W) {
  const Eigen::Vector2d d_W = q_W - box.p_W;
  const double c = std::cos(box.yaw_rad);
  const double s = std::sin(box.yaw_rad);
  // q in the box frame, folded into its first quadrant.
  const Eigen::Vector2d q_box(std::abs(c * d_W.x() + s * d_W.y()),
                              std::abs(-s * d_W.x() + c * d_W.y()));
  return (q_box - box.size_m / 2).cwiseMax(0.0).norm();
}

double CircumscribedRadius(const GroundBox& box) { return box.size_m.norm() / 2; }

}  // namespace aperture::planning
