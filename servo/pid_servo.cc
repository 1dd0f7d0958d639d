#include "servo/pid_servo.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/constants.h"
#include "control/require.h"

namespace aperture::servo {
namespace {

using control::kGravity_mps2;
constexpr double kMaxForwardPitchDeg = 30.0;
// x_B must lie this far in front of the image plane (z_C component of the unit x_B) to have a
// usable image: 0.1 = within ~84 deg of the optical axis.
constexpr double kMinBodyAxisDepth = 0.1;

// Unit direction of the image axis `axis_B` with its x_B component removed.
Eigen::Vector3d LateralDirection(const Eigen::Vector3d& axis_B) {
  Eigen::Vector3d lateral = axis_B;
  lateral.x() = 0.0;
  return lateral.normalized();
}

}  // namespace

void PidServoParams::Validate() const {
  control::RequireNonNegative(kp_mps, "PidServoParams.kp_mps");
  control::RequireNonNegative(ki_mps2, "PidServoParams.ki_mps2");
  control::RequireNonNegative(kd_m, "PidServoParams.kd_m");
  if (!std::isfinite(max_speed_mps) || max_speed_mps <= 0.0) {
    throw std::invalid_argument("PidServoParams.max_speed_mps = " + std::to_string(max_speed_mps) +
                                " must be finite and > 0 [m/s]");
  }
  if (!std::isfinite(forward_pitch_deg) || forward_pitch_deg < 0.0 ||
      forward_pitch_deg >= kMaxForwardPitchDeg) {
    throw std::invalid_argument(
        "PidServoParams.forward_pitch_deg = " + std::to_string(forward_pitch_deg) +
        " must lie in [0, 30) deg (theta_0 of GapFlyt Sec. III-B)");
  }
}

PidServo::PidServo(const PidServoParams& params, const Eigen::Isometry3d& T_BC,
                   double rotor_drag_dx_per_s)
    : params_(params), T_BC_(T_BC) {
  params_.Validate();
  RequireRigidMount(T_BC, "PidServo");
  if (!std::isfinite(rotor_drag_dx_per_s) || rotor_drag_dx_per_s <= 0.0) {
    throw std::invalid_argument(
        "PidServo: rotor_drag_dx_per_s = " + std::to_string(rotor_drag_dx_per_s) +
        " must be finite and > 0: the forward speed g tan(theta_0) / d_x needs the vehicle's "
        "rotor drag (VehicleParameters::rotor_drag_D_per_s.x())");
  }
  const Eigen::Matrix3d R_BC = T_BC.linear();
  const Eigen::Vector3d x_B_in_C = R_BC.transpose().col(0);
  if (x_B_in_C.z() < kMinBodyAxisDepth) {
    throw std::invalid_argument(
        "PidServo: the body's x axis is not in front of the camera (z_C component " +
        std::to_string(x_B_in_C.z()) +
        "); the GapFlyt PID needs a forward-looking camera mount T_BC");
  }
  body_axis_n_ = x_B_in_C.head<2>() / x_B_in_C.z();
  forward_speed_mps_ =
      kGravity_mps2 * std::tan(params_.forward_pitch_deg * M_PI / 180.0) / rotor_drag_dx_per_s;
  image_x_B_ = LateralDirection(R_BC.col(0));
  image_y_B_ = LateralDirection(R_BC.col(1));
}

void PidServo::Reset() {
  has_previous_ = false;
  previous_t_s_ = 0.0;
  previous_error_.setZero();
  integral_.setZero();
}

ServoStepResult PidServo::Step(double t_s, const Eigen::Vector2d& safe_point_n) {
  if (!std::isfinite(t_s) || !safe_point_n.allFinite()) {
    throw std::invalid_argument(
        "PidServo::Step: the time or the safe point is not finite; pass t_s [s] and x_s in "
        "normalized image coordinates");
  }
  if (has_previous_ && t_s <= previous_t_s_) {
    throw std::invalid_argument("PidServo::Step: t_s = " + std::to_string(t_s) +
                                " is not after the previous step's " +
                                std::to_string(previous_t_s_) + "; call Reset for a new run");
  }
  const Eigen::Vector2d error = safe_point_n - body_axis_n_;
  Eigen::Vector2d derivative = Eigen::Vector2d::Zero();
  if (has_previous_) {
    const double dt_s = t_s - previous_t_s_;
    derivative = (error - previous_error_) / dt_s;
    integral_ += error * dt_s;
    if (params_.ki_mps2 > 0.0) {
      const double limit = params_.max_speed_mps / params_.ki_mps2;
      integral_ = integral_.cwiseMax(-limit).cwiseMin(limit);
    }
  }
  has_previous_ = true;
  previous_t_s_ = t_s;
  previous_error_ = error;

  Eigen::Vector2d v_image = params_.kp_mps * error + params_.ki_mps2 * integral_ +
                            params_.kd_m * derivative;  // along image x, y [m/s]
  v_image = v_image.cwiseMax(-params_.max_speed_mps).cwiseMin(params_.max_speed_mps);

  ServoStepResult result;
  result.reference.v_B = forward_speed_mps_ * Eigen::Vector3d::UnitX() + v_image.x() * image_x_B_ +
                         v_image.y() * image_y_B_;
  result.twist_C = CameraTwistFromBodyVelocity(result.reference, T_BC_);
  result.error = error;
  result.error_norm = error.norm();
  return result;
}

}  // namespace aperture::servo
