#include "perception/pose_observation.h"

#include "control/so3.h"

namespace aperture::perception {

Eigen::Isometry3d PoseObservation::T_fixed_moving() const {
  return fixed == Fixed::kTarget ? Eigen::Isometry3d(T_CX.inverse()) : T_CX;
}

std::optional<Eigen::Matrix<double, 6, 6>> PoseObservation::covariance_fixed_moving() const {
  if (!covariance_CX || fixed == Fixed::kCamera) return covariance_CX;
  return control::InversePoseCovariance(T_CX, *covariance_CX);
}

}  // namespace aperture::perception
