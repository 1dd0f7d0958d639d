#include "control/drag_aided_odometry.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::control {

void DragAidedOdometryParams::Validate() const {
  attitude.Validate();
  height.Validate();
  RequirePositive(rotor_drag_xy_per_s.x(), "DragAidedOdometryParams.rotor_drag_xy_per_s.x");
  RequirePositive(rotor_drag_xy_per_s.y(), "DragAidedOdometryParams.rotor_drag_xy_per_s.y");
  RequirePositive(velocity_time_constant_s, "DragAidedOdometryParams.velocity_time_constant_s");
  RequirePositive(calibration_s, "DragAidedOdometryParams.calibration_s");
  RequirePositive(max_range_innovation_m, "DragAidedOdometryParams.max_range_innovation_m");
  RequirePositive(wind_residual_time_constant_s,
                  "DragAidedOdometryParams.wind_residual_time_constant_s");
  RequirePositive(wind_gate_mps, "DragAidedOdometryParams.wind_gate_mps");
  RequireNonNegative(wind_gate_sigmas, "DragAidedOdometryParams.wind_gate_sigmas");
  RequireNonNegative(max_wind_coast_s, "DragAidedOdometryParams.max_wind_coast_s");
  RequirePositive(max_correction_noise, "DragAidedOdometryParams.max_correction_noise");
}

DragAidedOdometry::DragAidedOdometry(const DragAidedOdometryParams& params)
    : params_(params), attitude_(params.attitude), height_(params.height) {
  params_.Validate();
}

void DragAidedOdometry::AddImu(double t_s, const Eigen::Vector3d& specific_force_B,
                               const Eigen::Vector3d& omega_B) {
  RequireFinite(t_s, "DragAidedOdometry::AddImu t_s");
  RequireFinite(specific_force_B, "DragAidedOdometry::AddImu specific_force_B");
  RequireFinite(omega_B, "DragAidedOdometry::AddImu omega_B");
  if (first_t_s_ && !(t_s > t_s_)) {
    throw std::invalid_argument("DragAidedOdometry::AddImu: t_s " + std::to_string(t_s) +
                                " is not after the previous sample's " + std::to_string(t_s_));
  }
  if (!calibrated_) {
    Calibrate(t_s, specific_force_B, omega_B);
  } else if (started_) {
    Propagate(t_s, specific_force_B, omega_B);
  } else {
    attitude_.AddImu(t_s, specific_force_B, omega_B);  // keeps the attitude until a range reading
  }
  t_s_ = t_s;
}

void DragAidedOdometry::Calibrate(double t_s, const Eigen::Vector3d& f_B,
                                  const Eigen::Vector3d& omega_B) {
  if (!first_t_s_) first_t_s_ = t_s;
  omega_sum_B_ += omega_B;
  f_xy_sum_B_ += f_B.head<2>();
  f_xy_squares_B_ += f_B.head<2>().cwiseAbs2();
  ++calibration_samples_;
  if (t_s - *first_t_s_ < params_.calibration_s) return;
  const double n = calibration_samples_;
  gyro_bias_B_ = omega_sum_B_ / n;
  accel_bias_xy_B_ = f_xy_sum_B_ / n;
  // The wind gate: the accelerometer's per-sample spread at rest, as drag velocity (/ d), through
  // the residual's low-pass (variance sigma^2 dt / (2 tau) for white noise at sample step dt).
  const Eigen::Vector2d variance_f =
      (f_xy_squares_B_ / n - accel_bias_xy_B_.cwiseAbs2()).cwiseMax(0.0);
  const double sigma_v_mps =
      variance_f.cwiseSqrt().cwiseQuotient(params_.rotor_drag_xy_per_s).maxCoeff();
  const double sample_dt_s = n > 1 ? (t_s - *first_t_s_) / (n - 1) : 0.0;
  const double sigma_lp_mps =
      sigma_v_mps * std::sqrt(sample_dt_s / (2.0 * params_.wind_residual_time_constant_s));
  wind_gate_mps_ = std::max(params_.wind_gate_mps, params_.wind_gate_sigmas * sigma_lp_mps);
  // The drag velocity's noise density q_v = sigma_v sqrt(dt); tau = q_v / max_correction_noise.
  velocity_time_constant_s_ =
      std::max(params_.velocity_time_constant_s,
               sigma_v_mps * std::sqrt(sample_dt_s) / params_.max_correction_noise);
  ImuAttitudeEstimatorParams attitude = params_.attitude;
  attitude.gyro_bias_B = gyro_bias_B_;
  attitude.accel_bias_B = Eigen::Vector3d(accel_bias_xy_B_.x(), accel_bias_xy_B_.y(), 0.0);
  attitude_ = ImuAttitudeEstimator(attitude);
  // At rest in hover z_B is vertical: the estimator starts level, at heading 0 (the frame W).
  attitude_.Reset(Eigen::Quaterniond::Identity());
  attitude_.AddImu(t_s, f_B, omega_B);
  calibrated_ = true;
  if (last_range_m_) AddRange(*last_range_m_);
}

void DragAidedOdometry::AddRange(double range_m) {
  RequireFinite(range_m, "DragAidedOdometry::AddRange range_m");
  if (!calibrated_) {
    last_range_m_ = range_m;
    return;
  }
  const std::optional<double> z_m = HeightFilter::HeightFromRange(range_m, attitude_.q_WB());
  if (!z_m) return;
  if (!started_) {
    height_.Initialize(*z_m, 0.0);
    p_W_ = Eigen::Vector3d(0.0, 0.0, *z_m);
    v_W_.setZero();
    started_ = true;
    return;
  }
  if (std::abs(*z_m - height_.estimate().z_m) > params_.max_range_innovation_m) {
    ++ranges_rejected_;
    return;
  }
  height_.Update(*z_m);
  p_W_.z() = height_.estimate().z_m;
}

void DragAidedOdometry::Propagate(double t_s, const Eigen::Vector3d& f_B,
                                  const Eigen::Vector3d& omega_B) {
  const double dt_s = t_s - t_s_;
  attitude_.AddImu(t_s, f_B, omega_B);
  omega_hat_B_ = attitude_.omega_B();
  const Eigen::Matrix3d R_WB = attitude_.q_WB().toRotationMatrix();
  const Eigen::Vector3d f_hat_B =
      f_B - Eigen::Vector3d(accel_bias_xy_B_.x(), accel_bias_xy_B_.y(), 0.0);
  const double g = params_.attitude.gravity_mps2;
  // Prediction: the acceleration the accelerometer measures.
  v_W_ += (R_WB * f_hat_B - g * Eigen::Vector3d::UnitZ()) * dt_s;
  height_.Predict(dt_s, HeightFilter::VerticalAcceleration(attitude_.q_WB(), f_hat_B, g));
  // Correction (F.2): the horizontal body velocity the rotor drag says.
  Eigen::Vector3d v_B = R_WB.transpose() * v_W_;
  const Eigen::Vector2d v_drag_B = -f_hat_B.head<2>().cwiseQuotient(params_.rotor_drag_xy_per_s);
  const Eigen::Vector2d residual_B = v_drag_B - v_B.head<2>();
  residual_lp_B_ += std::min(1.0, dt_s / params_.wind_residual_time_constant_s) *
                    (residual_B - residual_lp_B_);
  coasting_ = residual_lp_B_.norm() > wind_gate_mps_ && coast_s_ < params_.max_wind_coast_s;
  if (coasting_) {
    coast_s_ += dt_s;  // wind: the prediction alone
  } else {
    if (residual_lp_B_.norm() <= wind_gate_mps_) coast_s_ = 0.0;
    const double k = std::min(1.0, dt_s / velocity_time_constant_s_);
    v_B.head<2>() += k * residual_B;
  }
  v_W_ = R_WB * v_B;
  v_W_.z() = height_.estimate().z_dot_mps;
  p_W_.head<2>() += v_W_.head<2>() * dt_s;
  p_W_.z() = height_.estimate().z_m;
}

QuadState DragAidedOdometry::estimate() const {
  QuadState state;
  if (!started_) return state;
  state.t_s = t_s_;
  state.p_WB = p_W_;
  state.v_W = v_W_;
  state.q_WB = attitude_.q_WB();
  state.omega_B = omega_hat_B_;
  return state;
}

}  // namespace aperture::control
