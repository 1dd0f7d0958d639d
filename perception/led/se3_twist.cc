#include "perception/led/se3_twist.h"

#include <cmath>

namespace aperture::perception {
namespace {

// Left Jacobian of SO(3): V in exp([rho; phi]^) = [exp(phi^), V rho].
Eigen::Matrix3d LeftJacobianSo3(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  const Eigen::Matrix3d K = Skew(phi);
  if (angle < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * K;
  const double a2 = angle * angle;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(angle)) / a2 * K +
         (angle - std::sin(angle)) / (a2 * angle) * K * K;
}

}  // namespace

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
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

}  // namespace aperture::perception
