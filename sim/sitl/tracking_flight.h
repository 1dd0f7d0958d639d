#pragma once
// One trajectory-tracking flight in the SITL (the thesis' motion-capture experiments F.7, G.6):
// the vehicle starts hovering at the reference's start point, TrajectoryTrackingAutopilot flies
// the reference on ground truth at control_rate_hz, the simulated flight controller runs the
// configured body-rate law, mixer and saturation at 1 kHz on the noisy IMU gyro, and the tracking
// error against the reference is measured on the ground-truth trajectory.
//
//   TrackingFlightParams params;
//   params.reference = std::make_shared<control::CircleTrajectory>();
//   params.control.position.compensate_rotor_drag = false;
//   TrackingFlightResult flight = FlyTrackingFlight(params);
//   flight.error.E_a_m   // (F.39) over [error_begin_s, error_end_s]
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "control/quad_state.h"
#include "control/reference_trajectories.h"
#include "control/vehicle_parameters.h"
#include "sim/control_params_io.h"
#include "sim/sitl/sitl_runner.h"
#include "sim/sitl/vehicle_mismatch.h"

namespace aperture::sim {

// Position error statistics of a flown trajectory against its reference, E_p^k = p^k - p_ref^k.
struct TrackingError {
  int samples = 0;
  double E_a_m = 0.0;  // sqrt(mean |E_p|^2), Faessler thesis (F.39)
  double max_m = 0.0;  // max |E_p|
  double std_m = 0.0;  // standard deviation of |E_p| (Table F.1's sigma(||E_p||))
  Eigen::Vector3d rmse_W_m = Eigen::Vector3d::Zero();  // per-axis RMSE [m]
};

// Errors of the states with t in [begin_s, end_s] against reference.Evaluate(t). Throws
// std::invalid_argument when no state falls into the window.
TrackingError ComputeTrackingError(const std::vector<control::QuadState>& trajectory,
                                   const control::ReferenceTrajectory& reference, double begin_s,
                                   double end_s);

struct TrackingFlightParams {
  std::shared_ptr<const control::ReferenceTrajectory> reference;  // required
  ControlStackParams control;        // controller gains, drag switch, body rates, mixer
  QuadrotorDynamicsParams dynamics;  // the simulated vehicle (d_x = 0.5, d_y = 0.35 1/s)
  // The controller's vehicle model; unset = the simulated vehicle (perfectly identified). Drag
  // identification flies with candidate drag coefficients here.
  std::optional<control::VehicleParameters> controller_model;
  // vehicle.mismatch: the simulated vehicle departs from `dynamics` (which stays the flight
  // controller's model) by a VehicleMismatch drawn from `seed` (sim/sitl/vehicle_mismatch.h).
  VehicleMismatchParams vehicle;
  ImuSensorParams imu;             // realistic noise by default; its seed is set from `seed`
  std::uint64_t seed = 1;          // every sensor stream (SitlRunnerParams::SetSeed)
  double control_rate_hz = 100.0;  // autopilot rate
  double settle_s = 1.0;           // flown after the reference ends [s]
  // Flight duration [s]; <= 0: reference end + settle_s (required for endless references). When
  // set, the vehicle holds the reference's end point until then.
  double duration_s = 0.0;
  double error_begin_s = 0.0;  // window of the tracking error [s] (clipped to the flight)
  double error_end_s = std::numeric_limits<double>::infinity();
  int trajectory_decimation = 10;  // ground truth kept at 100 Hz
  // Throws std::invalid_argument naming the field (null reference, endless reference without
  // duration, empty error window, invalid control parameters).
  void Validate() const;
};

struct TrackingFlightResult {
  SitlResult sitl;
  TrackingError error;
  std::vector<control::TrajectoryPoint> reference;  // at the times of sitl.trajectory
};

TrackingFlightResult FlyTrackingFlight(const TrackingFlightParams& params);

}  // namespace aperture::sim
