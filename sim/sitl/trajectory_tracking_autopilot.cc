#include "sim/sitl/trajectory_tracking_autopilot.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

namespace aperture::sim {

void TrajectoryTrackingAutopilotParams::Validate() const {
  if (!std::isfinite(settle_s) || settle_s < 0.0) {
    throw std::invalid_argument("TrajectoryTrackingAutopilotParams.settle_s = " +
                                std::to_string(settle_s) + " must be finite and >= 0");
  }
  controller.Validate();
}

TrajectoryTrackingAutopilot::TrajectoryTrackingAutopilot(
    const control::VehicleParameters& vehicle,
    std::shared_ptr<const control::ReferenceTrajectory> reference,
    const TrajectoryTrackingAutopilotParams& params)
    : reference_(std::move(reference)), params_(params), controller_(vehicle, params.controller) {
  if (!reference_) {
    throw std::invalid_argument("TrajectoryTrackingAutopilot: reference trajectory is null");
  }
  params_.Validate();
}

void TrajectoryTrackingAutopilot::OnGroundTruth(const control::QuadState& state) {
  state_ = state;
  have_state_ = true;
}

perception::AutopilotCommand TrajectoryTrackingAutopilot::Step(double t_s) {
  perception::AutopilotCommand command;
  last_t_s_ = t_s;
  if (!have_state_) return command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = controller_.Compute(state_, reference_->Evaluate(t_s)).command;
  command.done = t_s >= reference_->EndTimeS() + params_.settle_s;
  return command;
}

std::string TrajectoryTrackingAutopilot::status() const {
  const double end_s = reference_->EndTimeS();
  if (last_t_s_ >= end_s) return "holding end point";
  char buffer[64];
  if (std::isfinite(end_s)) {
    std::snprintf(buffer, sizeof(buffer), "tracking %.1f/%.1f s", last_t_s_, end_s);
  } else {
    std::snprintf(buffer, sizeof(buffer), "tracking %.1f s", last_t_s_);
  }
  return buffer;
}

}  // namespace aperture::sim
