#include "control/imu_attitude_estimator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::control {
void ImuAttitudeEstimatorParams::Validate() const {
  RequirePositive(correction_gain, "ImuAttitudeEstimatorParams.correction_gain");
  if (correction_gain > 1.0) {
    throw std::invalid_argument("ImuAttitudeEstimatorParams::correction_gain = " +
                                std::to_string(correction_gain) +
                                " must be <= 1 (k_corr of B.25 is a fraction of the angle)");
  }
  RequirePositive(max_update_rate_radps, "ImuAttitudeEstimatorParams.max_update_rate_radps");
  RequirePositive(max_accel_norm_error_mps2,
                  "ImuAttitudeEstimatorParams.max_accel_norm_error_mps2");
  RequirePositive(gravity_mps2, "ImuAttitudeEstimatorParams.gravity_mps2");
  if (!gyro_bias_B.allFinite() || !accel_bias_B.allFinite()) {
    throw std::invalid_argument("ImuAttitudeEstimatorParams: gyro_bias_B and accel_bias_B must be finite");
  }
}

ImuAttitudeEstimator::ImuAttitudeEstimator(const ImuAttitudeEstimatorParams& params)
    : params_(params) {
  params_.Validate();
}

void ImuAttitudeEstimator::Reset(const Eigen::Quaterniond& q_WB) {
  if (!q_WB.coeffs().allFinite() || !(q_WB.norm() > 0.0)) {
    throw std::invalid_argument("ImuAttitudeEstimator::Reset: q_WB must be finite and non-zero");
  }
  q_WB_ = q_WB.normalized();
  initialized_ = true;
  has_time_ = false;
}

bool ImuAttitudeEstimator::PassesUpdateGate(const Eigen::Vector3d& f_B,
                                            const Eigen::Vector3d& omega_hat_B) const {
  return omega_hat_B.norm() < params_.max_update_rate_radps &&
         std::abs(f_B.norm() - params_.gravity_mps2) < params_.max_accel_norm_error_mps2;
}

void ImuAttitudeEstimator::Correct(const Eigen::Vector3d& f_B) {
  const Eigen::Vector3d up_meas_B = f_B.normalized();
  const Eigen::Vector3d up_pred_B = q_WB_.conjugate() * Eigen::Vector3d::UnitZ();
  const double beta = std::acos(std::clamp(up_pred_B.dot(up_meas_B), -1.0, 1.0));  // (B.23)
  if (beta == 0.0) return;
  Eigen::Vector3d h_B = up_meas_B.cross(up_pred_B);  // (B.24)
  const double h_norm = h_B.norm();
  // Antiparallel: every axis orthogonal to up_pred_B is a shortest rotation.
  h_B = h_norm > 1e-12 ? Eigen::Vector3d(h_B / h_norm) : up_pred_B.unitOrthogonal();
  const Eigen::Quaterniond q_corr(
      Eigen::AngleAxisd(params_.correction_gain * beta, h_B));  // (B.25)
  q_WB_ = (q_WB_ * q_corr).normalized();                         // (B.26)
}

bool ImuAttitudeEstimator::AddImu(double t_s, const Eigen::Vector3d& specific_force_B,
                                  const Eigen::Vector3d& omega_B) {
  if (!std::isfinite(t_s) || (has_time_ && !(t_s > last_t_s_))) {
    throw std::invalid_argument("ImuAttitudeEstimator::AddImu: t_s = " + std::to_string(t_s) +
                                " must be finite and after the previous sample (" +
                                std::to_string(last_t_s_) + "); check the IMU timestamps");
  }
  if (!specific_force_B.allFinite() || !omega_B.allFinite()) {
    throw std::invalid_argument("ImuAttitudeEstimator::AddImu: non-finite IMU sample at t_s = " +
                                std::to_string(t_s));
  }
  const double dt = has_time_ ? t_s - last_t_s_ : 0.0;
  has_time_ = true;
  last_t_s_ = t_s;
  omega_hat_B_ = omega_B - params_.gyro_bias_B;
  const Eigen::Vector3d f_B = specific_force_B - params_.accel_bias_B;

  if (!initialized_) {
    if (!PassesUpdateGate(f_B, omega_hat_B_)) return false;
    // First gravity measurement: smallest rotation taking the measured up direction onto z_W.
    q_WB_ = Eigen::Quaterniond::FromTwoVectors(f_B, Eigen::Vector3d::UnitZ());
    initialized_ = true;
    return true;
  }

  // (B.22): zero-order integration, rate held over dt.
  const double rate = omega_hat_B_.norm();
  if (rate > 0.0 && dt > 0.0) {
    q_WB_ = (q_WB_ * Eigen::Quaterniond(Eigen::AngleAxisd(rate * dt, omega_hat_B_ / rate)))
                .normalized();
  }
  if (!PassesUpdateGate(f_B, omega_hat_B_)) return false;
  Correct(f_B);
  return true;
}

double ImuAttitudeEstimator::TiltRad() const {
  const double cos_tilt = (q_WB_ * Eigen::Vector3d::UnitZ()).z();
  return std::acos(std::clamp(cos_tilt, -1.0, 1.0));
}

Eigen::Vector3d ImuAttitudeEstimator::RollPitchYawRad() const {
  const Eigen::Matrix3d R = q_WB_.toRotationMatrix();
  return {std::atan2(R(2, 1), R(2, 2)), std::asin(std::clamp(-R(2, 0), -1.0, 1.0)),
          std::atan2(R(1, 0), R(0, 0))};
}

}  // namespace aperture::control
