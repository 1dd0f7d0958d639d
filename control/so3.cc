#include "control/so3.h"

#include <cmath>
#include <stdexcept>

namespace aperture::control {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

Eigen::Vector3d Vee(const Eigen::Matrix3d& S) {
  return 0.5 * Eigen::Vector3d(S(2, 1) - S(1, 2), S(0, 2) - S(2, 0), S(1, 0) - S(0, 1));
}

Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity() + Skew(phi);
  return Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
}

Eigen::Vector3d LogSo3(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd angle_axis(R);
  return angle_axis.angle() * angle_axis.axis();
}

Eigen::Quaterniond ExpQuaternion(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) {
    // First order; exact to round-off for such angles.
    return Eigen::Quaterniond(1.0, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z()).normalized();
  }
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, phi / angle));
}

Eigen::Vector3d LogQuaternion(const Eigen::Quaterniond& q) {
  const Eigen::AngleAxisd angle_axis(q.w() < 0.0 ? Eigen::Quaterniond(-q.coeffs()) : q);
  return angle_axis.angle() * angle_axis.axis();
}

Eigen::Quaterniond MeanRotation(const std::vector<Eigen::Quaterniond>& rotations) {
  if (rotations.empty()) throw std::invalid_argument("MeanRotation: no rotations to average");
  Eigen::Quaterniond mean = rotations.front().normalized();
  for (int iteration = 0; iteration < 20; ++iteration) {
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    for (const Eigen::Quaterniond& q : rotations) {
      step += LogQuaternion(mean.conjugate() * q.normalized());
    }
    step /= static_cast<double>(rotations.size());
    mean = (mean * ExpQuaternion(step)).normalized();
    if (step.norm() < 1e-12) break;
  }
  return mean;
}

Eigen::Matrix3d LeftJacobianSo3(const Eigen::Vector3d& phi) {
  // Barfoot (7.77): J_l = I + (1 - cos a) / a^2 [phi]x + (a - sin a) / a^3 [phi]x^2; the series
  // I + [phi]x / 2 below 1e-8 rad, where the closed form loses all digits to cancellation.
  const double angle = phi.norm();
  const Eigen::Matrix3d K = Skew(phi);
  if (angle < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * K;
  const double a2 = angle * angle;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(angle)) / a2 * K +
         (angle - std::sin(angle)) / (a2 * angle) * K * K;
}

Eigen::Isometry3d ExpSe3(const Vector6d& xi) {
  const Eigen::Vector3d phi = xi.tail<3>();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = ExpSo3(phi);
  T.translation() = LeftJacobianSo3(phi) * xi.head<3>();
  return T;
}

Vector6d LogSe3(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d phi = LogSo3(T.linear());
  Vector6d xi;
  xi.head<3>() = LeftJacobianSo3(phi).inverse() * T.translation();
  xi.tail<3>() = phi;
  return xi;
}

Matrix6d AdjointSe3(const Eigen::Isometry3d& T_AB) {
  Matrix6d Ad = Matrix6d::Zero();
  Ad.topLeftCorner<3, 3>() = T_AB.linear();
  Ad.topRightCorner<3, 3>() = Skew(T_AB.translation()) * T_AB.linear();
  Ad.bottomRightCorner<3, 3>() = T_AB.linear();
  return Ad;
}

Matrix6d InversePoseCovariance(const Eigen::Isometry3d& T_AB, const Matrix6d& covariance_AB) {
  const Matrix6d Ad = AdjointSe3(T_AB.inverse());
  return Ad * covariance_AB * Ad.transpose();
}

}  // namespace aperture::control
