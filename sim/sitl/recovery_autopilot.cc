#include "sim/sitl/recovery_autopilot.h"

#include <cmath>
#include <optional>
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
  if (!std::isfinite(hold_s) || hold_s < 0.0) {
    throw std::invalid_argument("RecoveryAutopilotParams.hold_s must be finite and >= 0");
  }
  vision.Validate();
}

RecoveryAutopilot::RecoveryAutopilot(const control::VehicleParameters& vehicle,
                                     const RecoveryAutopilotParams& params)
    : params_(params),
      pipeline_(vehicle, params.pipeline),
      vision_(params.vision, params.vision_seed) {
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
  // The vision pipeline initializes from the height stage (3) on (B.3.2), scaled by its height.
  const bool attempt =
      static_cast<int>(machine.stage()) >= static_cast<int>(control::RecoveryStage::kHeight) &&
      pipeline_.height_filter().initialized();
  control::QuadState truth = truth_;
  truth.t_s = t_s;
  const double estimated_height_m =
      attempt ? pipeline_.height_filter().estimate().z_m : truth.p_WB.z();
  if (vision_.Update(truth, attempt, estimated_height_m)) {
    const double heading_offset_rad =
        HeadingRad(pipeline_.attitude().q_WB()) - HeadingRad(truth_.q_WB);
    vision_.SetVisionRotation(
        Eigen::AngleAxisd(heading_offset_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix());
  }
  const std::optional<control::QuadState> vision = vision_.Estimate();
  if (vision) pipeline_.SetVisionState(*vision);
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
