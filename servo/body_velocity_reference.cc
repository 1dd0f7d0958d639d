#include "servo/body_velocity_reference.h"

#include <ostream>
#include <stdexcept>
#include <string>

#include "control/so3.h"

namespace aperture::servo {

std::ostream& operator<<(std::ostream& os, const BodyVelocityReference& reference) {
  return os << "v_B [" << reference.v_B.transpose() << "] m/s, yaw rate "
            << reference.yaw_rate_radps << " rad/s";
}

Eigen::Matrix<double, 6, 6> VelocityTwistMatrix(const Eigen::Isometry3d& T_AB) {
  return control::AdjointSe3(T_AB);  // [R, [t]x R; 0, R]
}

BodyVelocityReference BodyVelocityFromCameraTwist(const Twist& twist_C,
                                                  const Eigen::Isometry3d& T_BC) {
  if (!twist_C.allFinite()) {
    throw std::invalid_argument(
        "BodyVelocityFromCameraTwist: the camera twist has a non-finite entry; pass [v_C; "
        "omega_C] in m/s and rad/s");
  }
  if (!T_BC.matrix().allFinite()) {
    throw std::invalid_argument(
        "BodyVelocityFromCameraTwist: the camera mount T_BC has a non-finite entry");
  }
  const Twist twist_B = VelocityTwistMatrix(T_BC) * twist_C;
  BodyVelocityReference reference;
  reference.v_B = twist_B.head<3>();
  reference.yaw_rate_radps = twist_B[5];
  return reference;
}

Twist CameraTwistFromBodyVelocity(const BodyVelocityReference& reference,
                                  const Eigen::Isometry3d& T_BC) {
  Twist twist_B = Twist::Zero();
  twist_B.head<3>() = reference.v_B;
  twist_B[5] = reference.yaw_rate_radps;
  return VelocityTwistMatrix(T_BC.inverse()) * twist_B;
}

void RequireRigidMount(const Eigen::Isometry3d& T_BC, const char* who) {
  const Eigen::Matrix3d R_BC = T_BC.linear();
  if (!T_BC.matrix().allFinite() ||
      (R_BC.transpose() * R_BC - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      R_BC.determinant() < 0.0) {
    throw std::invalid_argument(std::string(who) +
                                ": the camera mount T_BC is not a rigid transform (finite, "
                                "rotation orthonormal with determinant +1)");
  }
}

}  // namespace aperture::servo
