#include "control/recovery_state_machine.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::control {
namespace {

// Heading of the current attitude in the sense of (B.16)-(B.18): angle of x_B projected on the
// x_W-y_W plane. Used as reference before the heading is locked, so no yaw rate is commanded.
double CurrentHeading(const Eigen::Quaterniond& q_WB) {
  const Eigen::Vector3d x_B_W = q_WB * Eigen::Vector3d::UnitX();
  return std::atan2(x_B_W.y(), x_B_W.x());
}

PositionControllerParams WithGains(PositionControllerParams params, bool p_xy, bool p_z,
                                   bool d_xy) {
  if (!p_xy) params.p_xy_per_s2 = 0.0;
  if (!p_z) params.p_z_per_s2 = 0.0;
  if (!d_xy) params.d_xy_per_s = 0.0;
  return params;
}

}  // namespace

const char* ToString(RecoveryStage stage) {
  switch (stage) {
    case RecoveryStage::kWaitingForLaunch: return "waiting_for_launch";
    case RecoveryStage::kAttitude: return "attitude";
    case RecoveryStage::kVerticalVelocity: return "vertical_velocity";
    case RecoveryStage::kHeight: return "height";
    case RecoveryStage::kHorizontalVelocity: return "horizontal_velocity";
    case RecoveryStage::kPosition: return "position";
  }
  return "unknown";
}

void RecoveryParams::Validate() const {
  RequireNonNegative(max_tilt_for_height_rad, "RecoveryParams.max_tilt_for_height_rad");
  RequireNonNegative(max_roll_pitch_rate_radps, "RecoveryParams.max_roll_pitch_rate_radps");
  RequireNonNegative(max_vertical_speed_mps, "RecoveryParams.max_vertical_speed_mps");
  RequireNonNegative(max_horizontal_speed_mps, "RecoveryParams.max_horizontal_speed_mps");
  RequireNonNegative(min_height_filter_time_s, "RecoveryParams.min_height_filter_time_s");
  controller.Validate();
}

RecoveryStateMachine::RecoveryStateMachine(const VehicleParameters& vehicle,
                                           const RecoveryParams& params)
    : vehicle_(vehicle),
      params_((params.Validate(), params)),
      attitude_controller_(params.controller.attitude),
      // B.3.2: stage 2 P_pos = 0, d_xy = 0; stage 3 p_xy = d_xy = 0; stage 4 p_xy = 0.
      vertical_velocity_controller_(vehicle, WithGains(params.controller, false, false, false)),
      height_controller_(vehicle, WithGains(params.controller, false, true, false)),
      horizontal_velocity_controller_(vehicle, WithGains(params.controller, false, true, true)),
      position_controller_(vehicle, params.controller) {}

void RecoveryStateMachine::Reset() {
  stage_ = RecoveryStage::kWaitingForLaunch;
  stage_entry_t_s_ = 0.0;
  reference_height_m_ = 0.0;
  reference_z_vision_m_ = 0.0;
  locked_position_W_.setZero();
  locked_heading_rad_ = 0.0;
  transitions_.clear();
}

void RecoveryStateMachine::StartWithoutLaunch(double t_s) {
  Reset();
  RecoveryInputs in;
  in.t_s = t_s;
  Advance(in);
}

bool RecoveryStateMachine::ExitConditionHolds(const RecoveryInputs& in) const {
  switch (stage_) {
    case RecoveryStage::kWaitingForLaunch:
      return in.launch_detected;  // (B.29)
    case RecoveryStage::kAttitude: {
      const double tilt =
          std::acos(std::clamp((in.q_WB * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0));
      return tilt < params_.max_tilt_for_height_rad &&
             in.omega_B.head<2>().norm() < params_.max_roll_pitch_rate_radps;
    }
    case RecoveryStage::kVerticalVelocity:
      return in.height && in.height->time_since_init_s >= params_.min_height_filter_time_s &&
             std::abs(in.height->z_dot_mps) < params_.max_vertical_speed_mps;
    case RecoveryStage::kHeight:
      return in.height && in.vision_state.has_value();
    case RecoveryStage::kHorizontalVelocity:
      return in.vision_state->v_W.head<2>().norm() < params_.max_horizontal_speed_mps;
    case RecoveryStage::kPosition:
      return false;  // until a new mission takes over
  }
  return false;
}

void RecoveryStateMachine::Advance(const RecoveryInputs& in) {
  const RecoveryStage next = static_cast<RecoveryStage>(static_cast<int>(stage_) + 1);
  switch (next) {
    case RecoveryStage::kHeight:
      reference_height_m_ = in.height->z_m;
      break;
    case RecoveryStage::kHorizontalVelocity:
      reference_z_vision_m_ = in.vision_state->p_WB.z();
      break;
    case RecoveryStage::kPosition:
      locked_position_W_ = in.vision_state->p_WB;
      locked_heading_rad_ = CurrentHeading(in.q_WB);
      break;
    default:
      break;
  }
  transitions_.push_back({in.t_s, stage_, next});
  stage_ = next;
  stage_entry_t_s_ = in.t_s;
}

ThrustRatesCommand RecoveryStateMachine::ComputeCommand(const RecoveryInputs& in) const {
  const Eigen::Quaterniond q_WB = in.q_WB.normalized();
  const bool needs_height =
      stage_ == RecoveryStage::kVerticalVelocity || stage_ == RecoveryStage::kHeight;
  if (stage_ == RecoveryStage::kWaitingForLaunch) return {};  // rotors idle
  if (stage_ == RecoveryStage::kAttitude || (needs_height && !in.height)) {
    // Stage 1: level the vehicle with c = g.
    ThrustRatesCommand command;
    command.collective_thrust_mps2 = vehicle_.gravity_mps2;
    command.omega_des_B =
        attitude_controller_.Compute(q_WB, Eigen::Vector3d::UnitZ(), CurrentHeading(q_WB))
            .omega_fb_B;
    return command;
  }

  QuadState state;
  state.t_s = in.t_s;
  state.q_WB = q_WB;
  state.omega_B = in.omega_B;
  TrajectoryPoint reference;
  reference.t_s = in.t_s;
  reference.heading_rad = CurrentHeading(q_WB);
  const PositionController* controller = nullptr;
  if (needs_height) {
    // Horizontal position and velocity are unknown: their gains are zero, zero error is fed.
    state.p_WB = Eigen::Vector3d(0.0, 0.0, in.height->z_m);
    state.v_W = Eigen::Vector3d(0.0, 0.0, in.height->z_dot_mps);
    reference.p_W = state.p_WB;
    if (stage_ == RecoveryStage::kHeight) {
      reference.p_W.z() = reference_height_m_;
      controller = &height_controller_;
    } else {
      controller = &vertical_velocity_controller_;
    }
  } else {
    state.p_WB = in.vision_state->p_WB;
    state.v_W = in.vision_state->v_W;
    if (stage_ == RecoveryStage::kHorizontalVelocity) {
      reference.p_W = Eigen::Vector3d(state.p_WB.x(), state.p_WB.y(), reference_z_vision_m_);
      controller = &horizontal_velocity_controller_;
    } else {
      reference.p_W = locked_position_W_;
      reference.heading_rad = locked_heading_rad_;
      controller = &position_controller_;
    }
  }
  return controller->Compute(state, reference).command;
}

RecoveryOutput RecoveryStateMachine::Step(const RecoveryInputs& in) {
  if (!std::isfinite(in.t_s) || !in.q_WB.coeffs().allFinite() || !(in.q_WB.norm() > 0.0) ||
      !in.omega_B.allFinite()) {
    throw std::invalid_argument(
        "RecoveryStateMachine::Step: t_s, q_WB (non-zero) and omega_B must be finite");
  }
  if (in.height && !(std::isfinite(in.height->z_m) && std::isfinite(in.height->z_dot_mps))) {
    throw std::invalid_argument("RecoveryStateMachine::Step: height estimate is not finite");
  }
  const bool needs_vision =
      stage_ == RecoveryStage::kHorizontalVelocity || stage_ == RecoveryStage::kPosition;
  if (needs_vision && (!in.vision_state || !in.vision_state->IsValid())) {
    throw std::invalid_argument(
        std::string("RecoveryStateMachine::Step: stage '") + ToString(stage_) +
        "' needs a valid vision_state; after a vision failure call Reset() and recover again");
  }
  RecoveryOutput out;
  out.stage = stage_;
  out.command = ComputeCommand(in);
  if (ExitConditionHolds(in)) {
    Advance(in);
    out.initialize_height_filter = stage_ == RecoveryStage::kVerticalVelocity;
  }
  return out;
}

}  // namespace aperture::control
