#include "perception/pose_observation.h"

#include "perception/led/se3_twist.h"

namespace aperture::perception {

Eigen::Isometry3d PoseObservation::T_fixed_moving() const {
  return fixed == Fixed::kTarget ? Eigen::Isometry3d(T_CX.inverse()) : T_CX;
}

std::optional<Eigen::Matrix<double, 6, 6>> PoseObservation::covariance_fixed_moving() const {
  if (!covariance_CX || fixed == Fixed::kCamera) return covariance_CX;
  return CovarianceOfInverse(T_CX, *covariance_CX);
}

Eigen::Matrix<double, 6, 6> CovarianceOfInverse(const Eigen::Isometry3d& T_AB,
                                                const Eigen::Matrix<double, 6, 6>& covariance_AB) {
  const Eigen::Isometry3d T_BA = T_AB.inverse();
  Eigen::Matrix<double, 6, 6> Ad = Eigen::Matrix<double, 6, 6>::Zero();
  Ad.topLeftCorner<3, 3>() = T_BA.linear();
  Ad.topRightCorner<3, 3>() = Skew(T_BA.translation()) * T_BA.linear();
  Ad.bottomRightCorner<3, 3>() = T_BA.linear();
  return Ad * covariance_AB * Ad.transpose();
}

}  // namespace aperture::perception
