#pragma once
// SO(3) and SE(3) helpers, the one home for the hat/vee maps, the exponential and logarithm
// maps, the left Jacobian and the SE(3) adjoint (Barfoot, "State Estimation for Robotics",
// Sec. 7.1; Sola et al., "A micro Lie theory", arXiv:1812.01537).
//
// Conventions:
//   phi      rotation vector [rad]: R = Exp(phi) rotates by |phi| about phi / |phi|.
//   xi       twist [rho; phi] (translation part first): T = exp(xi^) = (Exp(phi), J_l(phi) rho).
//   delta    pose perturbation [dt; dr] (translation part first), applied on the left:
//            T_AB(delta) = (Exp(dr) R_AB, Exp(dr) p_AB + dt)  (so dt and dr are expressed in A).
// LogSo3 returns angles in [0, pi]; at exactly pi the sign of the axis is Eigen's choice.
// Nothing here throws; non-finite inputs give non-finite outputs.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace aperture::control {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// [v]x: Skew(a) * b = a x b.
Eigen::Matrix3d Skew(const Eigen::Vector3d& v);
// Inverse of Skew on skew-symmetric matrices (the skew-symmetric part of any other matrix).
Eigen::Vector3d Vee(const Eigen::Matrix3d& S);

// Rodrigues: rotation vector -> rotation matrix; first order below 1e-12 rad (exact to round-off).
Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& phi);
// Rotation matrix -> rotation vector with angle in [0, pi].
Eigen::Vector3d LogSo3(const Eigen::Matrix3d& R);
// The same maps on unit quaternions (the filter's attitude); LogQuaternion takes the shorter of
// q and -q, so its angle is in [0, pi].
Eigen::Quaterniond ExpQuaternion(const Eigen::Vector3d& phi);
Eigen::Vector3d LogQuaternion(const Eigen::Quaterniond& q);
// Geodesic (Karcher) mean of rotations that lie within a hemisphere of each other: Gauss-Newton
// on the sum of squared angles from the first (R <- R Exp(mean_k Log(R^T R_k))) until the step
// is below 1e-12 rad. Throws std::invalid_argument for an empty list.
Eigen::Quaterniond MeanRotation(const std::vector<Eigen::Quaterniond>& rotations);

// Left Jacobian of SO(3): Exp(phi + d) = Exp(J_l(phi) d) Exp(phi) to first order in d, and the
// V in exp(xi^) = (Exp(phi), J_l(phi) rho). The right Jacobian is J_r(phi) = J_l(-phi).
Eigen::Matrix3d LeftJacobianSo3(const Eigen::Vector3d& phi);

Eigen::Isometry3d ExpSe3(const Vector6d& xi);
Vector6d LogSe3(const Eigen::Isometry3d& T);

// Adjoint of T_AB for perturbations [dt; dr]: (Exp(delta_B) as a left perturbation in B, moved to
// A) delta_A = Ad(T_AB) delta_B, Ad = [R, [p]x R; 0, R].
Matrix6d AdjointSe3(const Eigen::Isometry3d& T_AB);

// Covariance of T_BA = T_AB^-1 over its left perturbation [dt; dr] (in B), given the covariance
// of T_AB over its left perturbation (in A): T_BA Exp(-delta) = Exp(-Ad(T_BA) delta) T_BA.
Matrix6d InversePoseCovariance(const Eigen::Isometry3d& T_AB, const Matrix6d& covariance_AB);

}  // namespace aperture::control
