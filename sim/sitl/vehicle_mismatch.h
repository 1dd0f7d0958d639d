#pragma once
// A simulated vehicle that is not the controllers' model (issue 21, item 1). The controllers keep
// the nominal control::VehicleParameters; the simulated vehicle departs from it by a
// VehicleMismatch drawn per trial (from the trial's seed) within VehicleMismatchBounds:
//   * drag: d_x, d_y of (F.2) off by a factor, k_h of (F.5) != 0 (F.7.3 identified 0.009 1/m),
//     parasitic drag quadratic in airspeed and rotor drag growing with thrust
//     (QuadrotorDynamicsParams::quadratic_drag_per_m, drag_thrust_exponent);
//   * rotors: time constants alpha_up, alpha_dwn of (G.7), thrust map (G.3) and torque map (G.4)
//     off by a factor, per-motor fitness gamma_i (G.2 text) != 1, battery sag;
//   * loop: ESC delay, extra gyro noise from vibration (white, added to the IMU's density),
//     command latency (autopilot -> flight controller) and estimate latency (ground truth ->
//     autopilot; SitlRunnerParams).
// The factors are relative, so a caller may change the nominal model first (e.g. the command
// range of a saturation test) and apply the mismatch last.
//
//   sim::SitlRunnerParams sitl = ...;            // dynamics.vehicle: the nominal model
//   ApplyVehicleMismatch(DrawVehicleMismatch(bounds, seed), &sitl);
//   // sitl.flight_controller_model = nominal, sitl.dynamics = the drawn vehicle; autopilots are
//   // built on the nominal model as before.
//
// Config section `vehicle` (VehicleMismatchParams, sim/sim_params_io.h):
//   vehicle: {mismatch: true, mismatch_bounds: {thrust_map_relative: 0.3, ...}}
#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "sim/sitl/sitl_runner.h"

namespace aperture::sim {

// Each relative bound b draws a factor 1 + U(-b, b); each *_max draws U(0, max); the latencies
// U(min, max). Defaults: the ranges of issue 21.
struct VehicleMismatchBounds {
  double rotor_drag_relative = 0.2;            // d_x, d_y of (F.2), independently
  double thrust_velocity_coeff_kh_max = 0.02;  // k_h of (F.5) added to the nominal [1/m]
  double quadratic_drag_max_per_m = 0.03;      // parasitic drag c_q [1/m]
  double drag_thrust_exponent_max = 0.5;       // D ~ (thrust / hover thrust)^e
  double time_constant_relative = 0.3;         // alpha_up, alpha_dwn of (G.7), independently
  double thrust_map_relative = 0.3;            // (G.3), all rotors alike
  double torque_map_relative = 0.3;            // (G.4), all rotors alike
  double rotor_fitness_relative = 0.1;         // gamma_i per rotor
  double battery_sag_max_per_s = 0.001;        // thrust fraction lost per second of flight
  double esc_delay_max_s = 0.005;              // [s]
  double gyro_vibration_noise_max = 2e-3;      // added gyro white-noise density [rad/s/sqrt(Hz)]
  Eigen::Vector2d command_latency_s{0.01, 0.015};   // [min, max] autopilot -> flight controller
  Eigen::Vector2d estimate_latency_s{0.01, 0.015};  // [min, max] ground truth -> autopilot
  // Throws std::invalid_argument naming the field: negative or non-finite values, relative
  // bounds >= 1 (a factor must stay positive), exponent above 2, latency min > max.
  void Validate() const;
};

// The config section `vehicle`: mismatch off reproduces the vehicle = model benches.
struct VehicleMismatchParams {
  bool mismatch = false;
  VehicleMismatchBounds mismatch_bounds;
  // With mismatch: the flight controller flies with the collective thrust scale a hover thrust
  // calibration (thesis A.5.4) identifies (CalibrateHoverThrust); false: the raw nominal maps,
  // whose thrust error leaves the height loop (no integrator) g (1/s - 1) / p_z low.
  bool hover_thrust_calibration = true;
  void Validate() const { mismatch_bounds.Validate(); }
};

// One drawn vehicle, relative to the nominal model (factors) or absolute (additions).
struct VehicleMismatch {
  Eigen::Vector2d rotor_drag_factor_xy = Eigen::Vector2d::Ones();
  double thrust_velocity_coeff_kh = 0.0;  // added [1/m]
  double quadratic_drag_per_m = 0.0;
  double drag_thrust_exponent = 0.0;
  double time_constant_up_factor = 1.0;
  double time_constant_down_factor = 1.0;
  double thrust_map_factor = 1.0;
  double torque_map_factor = 1.0;
  Eigen::Vector4d rotor_fitness_factor = Eigen::Vector4d::Ones();
  double battery_sag_per_s = 0.0;
  double esc_delay_s = 0.0;
  double gyro_vibration_noise = 0.0;  // [rad/s/sqrt(Hz)]
  double command_latency_s = 0.0;
  double estimate_latency_s = 0.0;
};

// Deterministic in (bounds, seed); its own stream (independent of SitlRunnerParams::SetSeed's).
// Throws like bounds.Validate().
VehicleMismatch DrawVehicleMismatch(const VehicleMismatchBounds& bounds, std::uint64_t seed);

// The simulated vehicle's parameters: `nominal` with the drag, rotor and fitness departures of
// `mismatch` (the rest of it acts through QuadrotorDynamicsParams and SitlRunnerParams).
control::VehicleParameters MismatchedVehicle(const control::VehicleParameters& nominal,
                                             const VehicleMismatch& mismatch);

// `sitl->dynamics.vehicle` is the nominal model: it becomes the flight controller's model (unless
// one is set already) and the simulated vehicle departs from it by `mismatch`; the latencies and
// ESC delay are added to sitl's, the vibration noise to the IMU's gyro density (in quadrature).
void ApplyVehicleMismatch(const VehicleMismatch& mismatch, SitlRunnerParams* sitl);

// The collective part of the hover thrust calibration (A.23)-(A.29) done perfectly: in hover
// with equal true rotor thrusts the flight controller's nominal thrusts sum to
// m g / (s_f mean_h(gamma_i)) (mean_h: harmonic mean), so lambda = s_f mean_h(gamma_i) and the
// flight controller's thrust and torque maps (G.3), (G.4) are scaled by it (the torque follows
// the command, A.27 text). Per-rotor gamma_i, the torque-map factor, the time constants, drag,
// sag and latencies stay unknown to it. Requires sitl->flight_controller_model (ApplyVehicle-
// Mismatch sets it); returns lambda.
double CalibrateHoverThrust(const VehicleMismatch& mismatch, SitlRunnerParams* sitl);

// When params.mismatch: draws from `seed`, applies (and calibrates the hover thrust when
// params.hover_thrust_calibration) and returns the draw; else leaves `sitl` as it is and returns
// nullopt.
std::optional<VehicleMismatch> ApplyVehicleMismatch(const VehicleMismatchParams& params,
                                                    std::uint64_t seed, SitlRunnerParams* sitl);

}  // namespace aperture::sim
