#include "experiments/tags/image_centre_offset.h"

namespace aperture::experiments {

std::optional<double> ImageCentreOffset(const control::QuadState& x, const Eigen::Isometry3d& T_BC,
                                        const perception::CameraModel& camera,
                                        const Eigen::Vector3d& p_W) {
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.linear() = x.q_WB.toRotationMatrix();
  T_WB.translation() = x.p_WB;
  Eigen::Vector2d px;
  if (!camera.Project((T_WB * T_BC).inverse() * p_W, &px)) return std::nullopt;
  const Eigen::Vector2d centre_px(0.5 * (camera.width() - 1), 0.5 * (camera.height() - 1));
  return (px - centre_px).norm() / camera.width();
}

}  // namespace aperture::experiments
