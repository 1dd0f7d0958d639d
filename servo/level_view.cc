#include "servo/level_view.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace aperture::servo {

std::optional<std::vector<Eigen::Vector2d>> LevelView(const std::vector<Eigen::Vector2d>& points_n,
                                                      const Eigen::Matrix3d& R_WB,
                                                      const Eigen::Matrix3d& R_BC) {
  if (!R_WB.allFinite() || !R_BC.allFinite()) {
    throw std::invalid_argument("LevelView: the attitude R_WB or the mount R_BC is not finite");
  }
  // Heading of x_B (F.9-style: the yaw of x_B projected on the x_W-y_W plane).
  const double psi = std::atan2(R_WB(1, 0), R_WB(0, 0));
  const Eigen::Matrix3d R_WBlevel =
      Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d R_ClevelC = R_BC.transpose() * R_WBlevel.transpose() * R_WB * R_BC;
  std::vector<Eigen::Vector2d> level;
  level.reserve(points_n.size());
  for (const Eigen::Vector2d& p : points_n) {
    if (!p.allFinite()) throw std::invalid_argument("LevelView: an image point is not finite");
    const Eigen::Vector3d ray = R_ClevelC * Eigen::Vector3d(p.x(), p.y(), 1.0);
    if (ray.z() <= 1e-9) return std::nullopt;
    level.push_back(ray.head<2>() / ray.z());
  }
  return level;
}

}  // namespace aperture::servo
