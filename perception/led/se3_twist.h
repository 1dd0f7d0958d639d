#pragma once
// SE(3) <-> twist coordinates xi = [rho; phi] (T = exp(xi^), phi the rotation vector), used by
// the LED tracker's constant-velocity prediction (Faessler thesis (C.6)) and its Gauss-Newton
// refinement.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace aperture::perception {

using Vector6d = Eigen::Matrix<double, 6, 1>;

Eigen::Matrix3d Skew(const Eigen::Vector3d& v);
// Rotation vector -> rotation matrix (Rodrigues) and back (angle in [0, pi]).
Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& phi);
Eigen::Vector3d LogSo3(const Eigen::Matrix3d& R);
Eigen::Isometry3d ExpSe3(const Vector6d& xi);
Vector6d LogSe3(const Eigen::Isometry3d& T);

}  // namespace aperture::perception
