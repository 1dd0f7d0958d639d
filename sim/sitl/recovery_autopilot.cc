#include "sim/sitl/recovery_autopilot.h"

#include <cmath>
#include <stdexcept>

namespace aperture::sim {
namespace {

// Heading of x_B projected onto the horizontal plane [rad] (thesis F.9, B.16).
double HeadingRad(const Eigen::Quaterniond& q_WB) {
  const Eigen::Vector3d x_B = q_WB * Eigen::Vector3d::UnitX();
  return std::atan2(x_B.y(), x_B.x());
}

}  // namespace

void RecoveryAutopilotParams::Validate() const {
  if (!std::isfinite(vision_delay_s) || vision_delay_s < 0.0) {
    throw std::invalid_argument("RecoveryAutopilotParams.vision_delay_s must be finite and >= 0");
  }
  if (!std::isfinite(hold_s) || hold_s < 0.0) {
    throw std::invalid_argument("RecoveryAutopilotParams.hold_s must be finite and >= 0");
  }
  if (!vision_offset_W.allFinite()) {
    throw std::invalid_argument("RecoveryAutopilotParams.vision_offset_W must be finite");
  }
}

RecoveryAutopilot::RecoveryAutopilot(const control::VehicleParameters& vehicle,
                                     const RecoveryAutopilotParams& params)
    : params_(params), pipeline_(vehicle, params.pipeline) {
  params_.Validate();
}

void RecoveryAutopilot::OnImu(const perception::ImuSample& sample) {
  pipeline_.AddImu(sample.t_s, sample.specific_force_B, sample.omega_B);
}

void RecoveryAutopilot::OnRange(const perception::RangeReading& reading) {
  if (reading.valid) pipeline_.AddRange(reading.range_m);
}

perception::AutopilotCommand RecoveryAutopilot::Step(double t_s) {
  const control::RecoveryStateMachine& machine = pipeline_.state_machine();
  if (vision_available_s_ < 0.0 && machine.stage() == control::RecoveryStage::kHeight &&
      t_s - machine.stage_entry_time_s() >= params_.vision_delay_s - 1e-9) {
    vision_available_s_ = t_s;
    const double heading_offset_rad =
        HeadingRad(pipeline_.attitude().q_WB()) - HeadingRad(truth_.q_WB);
    R_VW_ = Eigen::AngleAxisd(heading_offset_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  if (vision_available_s_ >= 0.0) {
    control::QuadState vision = truth_;
    vision.p_WB = R_VW_ * truth_.p_WB + params_.vision_offset_W;
    vision.v_W = R_VW_ * truth_.v_W;
    vision.q_WB = Eigen::Quaterniond(R_VW_) * truth_.q_WB;
    pipeline_.SetVisionState(vision);
  }
  const control::RecoveryOutput out = pipeline_.Step(t_s);
  perception::AutopilotCommand command;
  if (out.stage != control::RecoveryStage::kWaitingForLaunch) {
    command.kind = perception::AutopilotCommand::Kind::kThrustRates;
    command.thrust_rates = out.command;
  }
  command.done = machine.stage() == control::RecoveryStage::kPosition &&
                 t_s - machine.stage_entry_time_s() >= params_.hold_s;
  return command;
}

std::string RecoveryAutopilot::status() const {
  return std::string("stage ") +
         std::to_string(static_cast<int>(pipeline_.state_machine().stage())) + " " +
         control::ToString(pipeline_.state_machine().stage());
}

}  // namespace aperture::sim
