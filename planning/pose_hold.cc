#include "planning/pose_hold.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "control/require.h"
#include "control/trajectory_point.h"

namespace aperture::planning {
namespace {

// Largest gap between control steps integrated at once [s]: a stalled caller must not wind up
// the integral in one step.
constexpr double kMaxIntegrationStep_s = 0.1;

}  // namespace

void PoseHoldParams::Validate() const {
  filter.Validate();
  controller.Validate();
  if (!std::isfinite(integral_gain_per_s3) || integral_gain_per_s3 < 0.0) {
    throw std::invalid_argument("PoseHoldParams.integral_gain_per_s3 must be finite and >= 0, got " +
                                std::to_string(integral_gain_per_s3));
  }
  if (!std::isfinite(max_integral_accel_mps2) || max_integral_accel_mps2 < 0.0) {
    throw std::invalid_argument(
        "PoseHoldParams.max_integral_accel_mps2 must be finite and >= 0, got " +
        std::to_string(max_integral_accel_mps2));
  }
  if (!std::isfinite(disturbance_time_constant_s) || disturbance_time_constant_s < 0.0) {
    throw std::invalid_argument(
        "PoseHoldParams.disturbance_time_constant_s must be finite and >= 0, got " +
        std::to_string(disturbance_time_constant_s));
  }
  if (!std::isfinite(max_disturbance_accel_mps2) || max_disturbance_accel_mps2 < 0.0) {
    throw std::invalid_argument(
        "PoseHoldParams.max_disturbance_accel_mps2 must be finite and >= 0, got " +
        std::to_string(max_disturbance_accel_mps2));
  }
  if (!std::isfinite(max_integrated_error_m) || max_integrated_error_m <= 0.0) {
    throw std::invalid_argument("PoseHoldParams.max_integrated_error_m must be positive, got " +
                                std::to_string(max_integrated_error_m));
  }
  if (!std::isfinite(max_position_error_m) || max_position_error_m <= 0.0) {
    throw std::invalid_argument("PoseHoldParams.max_position_error_m must be positive, got " +
                                std::to_string(max_position_error_m));
  }
  if (!std::isfinite(max_pose_age_s) || max_pose_age_s <= 0.0) {
    throw std::invalid_argument("PoseHoldParams.max_pose_age_s must be positive, got " +
                                std::to_string(max_pose_age_s));
  }
  if (max_consecutive_rejections < 1) {
    throw std::invalid_argument("PoseHoldParams.max_consecutive_rejections must be >= 1, got " +
                                std::to_string(max_consecutive_rejections));
  }
  perception::RequireProcessNoiseScale(max_process_noise_scale,
                                       "PoseHoldParams.max_process_noise_scale");
}

PoseHold::PoseHold(const control::VehicleParameters& vehicle, const PoseHoldParams& params,
                   const PoseHoldSetpoint& setpoint)
    : params_((params.Validate(), params)),
      controller_(vehicle, params.controller),
      fusion_({params.filter, params.max_consecutive_rejections}) {
  fusion_.AdaptProcessNoise(params_.max_process_noise_scale);
  SetSetpoint(setpoint);
}

void PoseHold::SetSetpoint(const PoseHoldSetpoint& setpoint) {
  control::RequireFinite(setpoint.p_W, "PoseHoldSetpoint.p_W");
  control::RequireFinite(setpoint.heading_rad, "PoseHoldSetpoint.heading_rad");
  setpoint_ = setpoint;
}

void PoseHold::AddImu(const perception::ImuSample& sample) {
  fusion_.AddImu(sample);
  specific_force_sum_B_ += sample.specific_force_B;
  ++specific_force_count_;
}

std::vector<perception::PoseFusionOutcome> PoseHold::AddPose(
    const perception::PoseMeasurement& measurement) {
  return fusion_.AddPose(measurement);
}

std::optional<perception::PoseImuEstimate> PoseHold::estimate() const {
  return fusion_.estimate();
}

Eigen::Vector3d PoseHold::integral_accel_W() const {
  return params_.integral_gain_per_s3 * error_integral_W_;
}

perception::AutopilotCommand PoseHold::Step(double t_s) {
  control::RequireFinite(t_s, "PoseHold::Step t_s");
  perception::AutopilotCommand command;
  if (!fusion_.started()) return command;
  const perception::PoseImuEstimate estimate = *fusion_.estimate();
  const Eigen::Vector3d error_W = setpoint_.p_W - estimate.state.p_WB;
  if (stepped_ && params_.integral_gain_per_s3 > 0.0) {
    const double dt_s = std::clamp(t_s - last_step_t_s_, 0.0, kMaxIntegrationStep_s);
    Eigen::Vector3d integrated_error_W = error_W;
    if (integrated_error_W.norm() > params_.max_integrated_error_m) {
      integrated_error_W *= params_.max_integrated_error_m / integrated_error_W.norm();
    }
    error_integral_W_ += integrated_error_W * dt_s;
    const double max_integral = params_.max_integral_accel_mps2 / params_.integral_gain_per_s3;
    if (error_integral_W_.norm() > max_integral) {
      error_integral_W_ *= max_integral / error_integral_W_.norm();
    }
  }
  if (stepped_ && params_.disturbance_time_constant_s > 0.0 && specific_force_count_ > 0 &&
      last_collective_thrust_mps2_ > 0.0) {
    const double dt_s = std::clamp(t_s - last_step_t_s_, 0.0, kMaxIntegrationStep_s);
    const Eigen::Matrix3d R_WB = estimate.state.q_WB.toRotationMatrix();
    const Eigen::Vector3d a_ext_W =
        R_WB * (specific_force_sum_B_ / specific_force_count_ - estimate.accel_bias_B) -
        last_collective_thrust_mps2_ * R_WB.col(2);
    const double alpha = dt_s / (params_.disturbance_time_constant_s + dt_s);
    disturbance_accel_W_ += alpha * (a_ext_W - disturbance_accel_W_);
    if (disturbance_accel_W_.norm() > params_.max_disturbance_accel_mps2) {
      disturbance_accel_W_ *= params_.max_disturbance_accel_mps2 / disturbance_accel_W_.norm();
    }
  }
  stepped_ = true;
  last_step_t_s_ = t_s;
  specific_force_sum_B_.setZero();
  specific_force_count_ = 0;
  // A constant reference at most max_position_error_m from the estimate: the PD law sees a
  // clamped error, not a different goal.
  Eigen::Vector3d clamped_error_W = error_W;
  if (clamped_error_W.norm() > params_.max_position_error_m) {
    clamped_error_W *= params_.max_position_error_m / clamped_error_W.norm();
  }
  control::TrajectoryPoint reference;
  reference.t_s = t_s;
  reference.p_W = estimate.state.p_WB + clamped_error_W;
  reference.a_W = integral_accel_W() - disturbance_accel_W_;
  reference.heading_rad = setpoint_.heading_rad;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = controller_.Compute(estimate.state, reference).command;
  last_collective_thrust_mps2_ = command.thrust_rates.collective_thrust_mps2;
  return command;
}

std::string PoseHold::status(double t_s) const {
  if (!fusion_.started()) return "waiting for pose";
  const double age_s = t_s - fusion_.last_pose_t_s();
  if (age_s <= params_.max_pose_age_s) return "hold";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "hold, dead reckoning %.1f s", age_s);
  return buffer;
}

}  // namespace aperture::planning
