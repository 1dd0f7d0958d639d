#include "control/attitude_controller.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/flatness.h"  // kYawSingularity
#include "control/require.h"

namespace aperture::control {
namespace {

// Sign convention of (B.15): take the shorter way round.
double ShortWaySign(double w) { return w >= 0.0 ? 1.0 : -1.0; }

}  // namespace

void AttitudeControllerGains::Validate() const {
  RequireNonNegative(p_rp_per_s, "AttitudeControllerGains.p_rp_per_s");
  RequireNonNegative(p_yaw_per_s, "AttitudeControllerGains.p_yaw_per_s");
}

Eigen::Matrix3d ComputeDesiredAttitude(const Eigen::Vector3d& z_des_W, double heading_rad,
                                       bool* heading_defined) {
  const Eigen::Vector3d x_C(std::cos(heading_rad), std::sin(heading_rad), 0.0);  // (B.16)
  const Eigen::Vector3d y_C(-x_C.y(), x_C.x(), 0.0);                             // (B.17)
  Eigen::Vector3d x_tilde = y_C.cross(z_des_W);                                  // (B.18)
  const bool defined = x_tilde.norm() >= kYawSingularity;
  if (!defined) {
    x_tilde = x_C - x_C.dot(z_des_W) * z_des_W;  // |x_tilde| ~ 1 here
  } else if (z_des_W.z() < 0.0) {
    // B.18 text: with z_des pointing downwards y_C x z_des projects onto -x_C; negate it.
    x_tilde = -x_tilde;
  }
  if (heading_defined != nullptr) *heading_defined = defined;
  Eigen::Matrix3d R;
  R.col(0) = x_tilde.normalized();
  R.col(1) = z_des_W.cross(R.col(0)).normalized();  // (B.19)
  R.col(2) = z_des_W;
  return R;
}

AttitudeController::AttitudeController(const AttitudeControllerGains& gains) : gains_(gains) {
  gains_.Validate();
}

AttitudeFeedback AttitudeController::Compute(const Eigen::Quaterniond& q_WB,
                                             const Eigen::Vector3d& z_des_W,
                                             double heading_rad) const {
  const double z_norm = z_des_W.norm();
  if (!(z_norm > 0.0) || !std::isfinite(z_norm) || !q_WB.coeffs().allFinite() ||
      !std::isfinite(heading_rad)) {
    throw std::invalid_argument(
        "AttitudeController::Compute: q_WB, z_des_W and heading must be finite and z_des_W "
        "non-zero; check the state estimate and the desired acceleration");
  }
  const Eigen::Quaterniond q = q_WB.normalized();
  const Eigen::Matrix3d R = q.toRotationMatrix();
  const Eigen::Vector3d z_des = z_des_W / z_norm;
  const Eigen::Vector3d e_z = R.col(2);  // (B.10)

  AttitudeFeedback out;
  // (B.11)-(B.14): rotation taking e_z onto z_des, expressed in B.
  const double cos_alpha = std::clamp(e_z.dot(z_des), -1.0, 1.0);
  const double alpha = std::acos(cos_alpha);
  out.tilt_error_rad = alpha;
  const Eigen::Vector3d cross = e_z.cross(z_des);
  Eigen::Quaterniond q_e_rp = Eigen::Quaterniond::Identity();
  if (cross.norm() > 1e-12) {
    const Eigen::Vector3d n_B = R.transpose() * cross.normalized();  // (B.13)
    q_e_rp = Eigen::Quaterniond(Eigen::AngleAxisd(alpha, n_B));
  } else if (cos_alpha < 0.0) {
    q_e_rp = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
  }
  const double rp_sign = ShortWaySign(q_e_rp.w());
  out.omega_fb_B.x() = 2.0 * gains_.p_rp_per_s * rp_sign * q_e_rp.x();  // (B.15)
  out.omega_fb_B.y() = 2.0 * gains_.p_rp_per_s * rp_sign * q_e_rp.y();

  // (B.16)-(B.20): remaining rotation about z_des to the full desired attitude.
  out.R_des_WB = ComputeDesiredAttitude(z_des, heading_rad, &out.heading_defined);
  if (out.heading_defined) {
    const Eigen::Quaterniond q_des(out.R_des_WB);
    const Eigen::Quaterniond q_e_y = (q * q_e_rp).conjugate() * q_des;  // (B.20)
    out.omega_fb_B.z() = 2.0 * gains_.p_yaw_per_s * ShortWaySign(q_e_y.w()) * q_e_y.z();
  }
  return out;
}

}  // namespace aperture::control
