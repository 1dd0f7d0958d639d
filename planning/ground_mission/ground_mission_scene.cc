#include "planning/ground_mission/ground_mission_scene.h"

#include <array>
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

bool BoxesOverlap(const GroundBox& a, const GroundBox& b) {
  const Eigen::Vector2d d_W = b.p_W - a.p_W;
  const auto axes = [](const GroundBox& box) {
    const Eigen::Vector2d x(std::cos(box.yaw_rad), std::sin(box.yaw_rad));
    return std::array<Eigen::Vector2d, 2>{x, Eigen::Vector2d(-x.y(), x.x())};
  };
  const std::array<Eigen::Vector2d, 2> axes_a = axes(a);
  const std::array<Eigen::Vector2d, 2> axes_b = axes(b);
  // Half the extent of a box along the unit direction n.
  const auto half_extent = [](const GroundBox& box, const std::array<Eigen::Vector2d, 2>& box_axes,
                              const Eigen::Vector2d& n) {
    return 0.5 * (box.size_m.x() * std::abs(box_axes[0].dot(n)) +
                  box.size_m.y() * std::abs(box_axes[1].dot(n)));
  };
  for (const std::array<Eigen::Vector2d, 2>* box_axes : {&axes_a, &axes_b}) {
    for (const Eigen::Vector2d& n : *box_axes) {
      if (std::abs(d_W.dot(n)) >= half_extent(a, axes_a, n) + half_extent(b, axes_b, n)) {
        return false;
      }
    }
  }
  return true;
}

double CircumscribedRadius(const GroundBox& box) { return box.size_m.norm() / 2; }

}  // namespace aperture::planning
