#include "sim/sitl/tracking_flight.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/sitl/trajectory_tracking_autopilot.h"

namespace aperture::sim {
namespace {

double FlightDurationS(const TrackingFlightParams& params) {
  return params.duration_s > 0.0 ? params.duration_s
                                 : params.reference->EndTimeS() + params.settle_s;
}

}  // namespace

TrackingError ComputeTrackingError(const std::vector<control::QuadState>& trajectory,
                                   const control::ReferenceTrajectory& reference, double begin_s,
                                   double end_s) {
  TrackingError error;
  Eigen::Vector3d sum_squared_W = Eigen::Vector3d::Zero();
  double sum_norm_m = 0.0;
  for (const control::QuadState& state : trajectory) {
    if (state.t_s < begin_s || state.t_s > end_s) continue;
    const Eigen::Vector3d e_W = state.p_WB - reference.Evaluate(state.t_s).p_W;
    sum_squared_W += e_W.cwiseAbs2();
    sum_norm_m += e_W.norm();
    error.max_m = std::max(error.max_m, e_W.norm());
    ++error.samples;
  }
  if (error.samples == 0) {
    throw std::invalid_argument("ComputeTrackingError: no ground-truth state in the window [" +
                                std::to_string(begin_s) + ", " + std::to_string(end_s) +
                                "] s; widen it or fly longer");
  }
  error.rmse_W_m = (sum_squared_W / error.samples).cwiseSqrt();
  error.E_a_m = std::sqrt(sum_squared_W.sum() / error.samples);
  // Var|E_p| = mean |E_p|^2 - (mean |E_p|)^2, both over the window's samples.
  const double mean_norm_m = sum_norm_m / error.samples;
  error.std_m = std::sqrt(std::max(0.0, error.E_a_m * error.E_a_m - mean_norm_m * mean_norm_m));
  return error;
}

void TrackingFlightParams::Validate() const {
  if (!reference) throw std::invalid_argument("TrackingFlightParams.reference is null");
  if (!std::isfinite(duration_s) || (duration_s <= 0.0 && !std::isfinite(reference->EndTimeS()))) {
    throw std::invalid_argument(
        "TrackingFlightParams.duration_s must be set (> 0) for a reference that never stops");
  }
  if (!(error_begin_s < error_end_s) || error_begin_s > FlightDurationS(*this)) {
    throw std::invalid_argument("TrackingFlightParams: error window [" +
                                std::to_string(error_begin_s) + ", " + std::to_string(error_end_s) +
                                "] s misses the flight of " +
                                std::to_string(FlightDurationS(*this)) + " s");
  }
  if (trajectory_decimation < 1) {
    throw std::invalid_argument("TrackingFlightParams.trajectory_decimation must be >= 1");
  }
  control.Validate();
}

TrackingFlightResult FlyTrackingFlight(const TrackingFlightParams& params) {
  params.Validate();
  SitlRunnerParams sitl;
  sitl.duration_s = FlightDurationS(params);
  sitl.control_rate_hz = params.control_rate_hz;
  sitl.dynamics = params.dynamics;
  sitl.imu = params.imu;
  sitl.range_enabled = false;
  sitl.flight_controller.low_level = params.control.low_level;
  sitl.trajectory_decimation = params.trajectory_decimation;
  sitl.start_hovering = true;
  const control::TrajectoryPoint start = params.reference->Evaluate(0.0);
  sitl.initial_state.p_WB = start.p_W;
  sitl.initial_state.v_W = start.v_W;
  sitl.initial_state.q_WB = Eigen::AngleAxisd(start.heading_rad, Eigen::Vector3d::UnitZ());
  sitl.SetSeed(params.seed);
  ApplyVehicleMismatch(params.vehicle, params.seed, &sitl);

  TrajectoryTrackingAutopilotParams autopilot_params;
  autopilot_params.controller = params.control.position;
  // With an explicit duration the autopilot holds the end point until the run ends.
  autopilot_params.settle_s =
      params.duration_s > 0.0 && std::isfinite(params.reference->EndTimeS())
          ? std::max(params.settle_s, params.duration_s - params.reference->EndTimeS())
          : params.settle_s;
  TrajectoryTrackingAutopilot autopilot(params.controller_model.value_or(params.dynamics.vehicle),
                                        params.reference, autopilot_params);
  SitlRunner runner(sitl, nullptr);
  TrackingFlightResult result;
  result.sitl = runner.Run(autopilot);
  result.reference.reserve(result.sitl.trajectory.size());
  for (const control::QuadState& state : result.sitl.trajectory) {
    result.reference.push_back(params.reference->Evaluate(state.t_s));
  }
  result.error =
      ComputeTrackingError(result.sitl.trajectory, *params.reference, params.error_begin_s,
                           std::min(params.error_end_s, result.sitl.sim_time_s));
  return result;
}

}  // namespace aperture::sim
