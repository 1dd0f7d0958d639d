#include "sim/sitl/ground_truth_autopilot.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "control/trajectory_point.h"

namespace aperture::sim {

void GroundTruthAutopilotParams::Validate() const {
  if (waypoints.empty()) {
    throw std::invalid_argument(
        "GroundTruthAutopilotParams.waypoints is empty: give at least one (hover point)");
  }
  for (size_t i = 0; i < waypoints.size(); ++i) {
    const Waypoint& w = waypoints[i];
    if (!w.p_W.allFinite() || !std::isfinite(w.heading_rad) || !std::isfinite(w.hold_s) ||
        w.hold_s < 0.0) {
      throw std::invalid_argument("GroundTruthAutopilotParams.waypoints[" + std::to_string(i) +
                                  "] must be finite with hold_s >= 0");
    }
  }
  if (!std::isfinite(arrival_radius_m) || arrival_radius_m <= 0.0) {
    throw std::invalid_argument("GroundTruthAutopilotParams.arrival_radius_m must be positive");
  }
  if (!std::isfinite(max_position_error_m) || max_position_error_m <= 0.0) {
    throw std::invalid_argument("GroundTruthAutopilotParams.max_position_error_m must be positive");
  }
  controller.Validate();
}

GroundTruthAutopilot::GroundTruthAutopilot(const control::VehicleParameters& vehicle,
                                           const GroundTruthAutopilotParams& params)
    : params_(params), controller_(vehicle, params.controller) {
  params_.Validate();
}

void GroundTruthAutopilot::OnGroundTruth(const control::QuadState& state) {
  state_ = state;
  have_state_ = true;
}

perception::AutopilotCommand GroundTruthAutopilot::Step(double t_s) {
  perception::AutopilotCommand command;
  if (!have_state_) return command;
  const Waypoint& target = params_.waypoints[active_];
  const double distance_m = (state_.p_WB - target.p_W).norm();
  if (distance_m <= params_.arrival_radius_m) {
    if (arrived_since_s_ < 0.0) arrived_since_s_ = t_s;
    if (t_s - arrived_since_s_ >= target.hold_s) {
      if (active_ + 1 < static_cast<int>(params_.waypoints.size())) {
        ++active_;
        arrived_since_s_ = -1.0;
      } else {
        done_ = true;
      }
    }
  } else {
    arrived_since_s_ = -1.0;
  }
  const Waypoint& reference_waypoint = params_.waypoints[active_];
  // A constant reference placed at most max_position_error_m from the vehicle: the PD law sees a
  // clamped error, not a different goal.
  Eigen::Vector3d error_W = reference_waypoint.p_W - state_.p_WB;
  if (error_W.norm() > params_.max_position_error_m) {
    error_W *= params_.max_position_error_m / error_W.norm();
  }
  control::TrajectoryPoint reference;
  reference.t_s = t_s;
  reference.p_W = state_.p_WB + error_W;
  reference.heading_rad = reference_waypoint.heading_rad;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = controller_.Compute(state_, reference).command;
  command.done = done_ && params_.finish_when_done;
  return command;
}

std::string GroundTruthAutopilot::status() const {
  if (done_) return "holding final waypoint";
  return "waypoint " + std::to_string(active_ + 1) + "/" + std::to_string(params_.waypoints.size());
}

}  // namespace aperture::sim
