#pragma once
// YAML loaders (config::ParamReader, STYLE.md 6) for the simulated vehicle, its disturbances and
// sensors. Keys are the struct field names (they carry their units); absent keys keep the in-class
// defaults; unknown keys are rejected with the file, line and the list of known keys. Each loader
// ends with the struct's Validate(), so a loaded struct is always usable.
//
//   vehicle:                        # LoadVehicleParameters (control::VehicleParameters)
//     mass_kg: 0.45
//     inertia_diag_kgm2: [0.001, 0.001, 0.002]
//     rotor_drag_D_per_s: [0.5, 0.35, 0.0]
//     rotor_drag_A: [[0, 0, 0], [0, 0, 0], [0, 0, 0]]
//     rotor: {thrust_coeffs_N: [0.9, 1.6, 0.75], time_constant_up_s: 0.011}
//     rotor_fitness: [1, 1, 1, 1]
//   max_integration_step_s: 0.001   # QuadrotorDynamicsParams (the map above is its `vehicle`)
//   rotor_lag_enabled: true
//   ground_contact_enabled: false
//   ground_height_m: 0.0            # in the SITL also the collision checker's ground
//   landing_gear_height_m: 0.0      # origin of B above the ground when resting on the gear
//
//   disturbances:
//     steady_wind_W_mps: [0, 0, 0]
//     gusts: [[t_start_s, duration_s, wind_x, wind_y, wind_z], ...]       # W, m/s
//     pushes: [[t_s, J_x, J_y, J_z], [t_s, J_x, J_y, J_z, L_x, L_y, L_z]]  # J in W [N s], L in B [N m s]
//
//   imu: {rate_hz: 500, latency_s: 0.002, accel_noise_density: 3.9e-3, seed: 1, ...}
//   range: {rate_hz: 100, max_range_m: 14, max_tilt_rad: 0.52, p_BS: [0, 0, 0], seed: 2, ...}
//   collision: {body_radius_m: 0.08, propeller_radius_m: 0.0635, ground_enabled: true,
//               max_touchdown_speed_mps: 1.0, max_touchdown_tilt_rad: 0.5,
//               ignored_objects: [name, ...], sphere_rays: 64, disk_rays: 12}
//   sitl: {dynamics_rate_hz: 1000, control_rate_hz: 100, command_latency_s: 0,     # the loop
//          range_latency_s: 0, range_enabled: true, start_hovering: true}        # fields only
//
// All throw std::invalid_argument naming where the bad value is and what is expected.
#include "config/param_reader.h"
#include "control/vehicle_parameters.h"
#include "sim/sensors/imu_sensor.h"
#include "sim/sensors/odometry_sensor.h"
#include "sim/sensors/range_sensor.h"
#include "sim/sitl/collision_checker.h"
#include "sim/sitl/sitl_runner.h"
#include "sim/vehicle/disturbances.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::sim {

// control::VehicleParameters lives in `control`, which does not depend on `config`; its loader is
// here (call it directly: ReadSection cannot find it by argument-dependent lookup).
void LoadVehicleParameters(config::ParamReader& reader, control::VehicleParameters* params);

void LoadParams(config::ParamReader& reader, QuadrotorDynamicsParams* params);
void LoadParams(config::ParamReader& reader, DisturbanceParams* params);
void LoadParams(config::ParamReader& reader, ImuSensorParams* params);
void LoadParams(config::ParamReader& reader, RangeSensorParams* params);
// OdometrySensorParams: rate_hz, position_sigma_m, rotation_sigma_rad (the seed is the caller's).
void LoadParams(config::ParamReader& reader, OdometrySensorParams* params);
void LoadParams(config::ParamReader& reader, CollisionParams* params);
// The loop fields of SitlRunnerParams only (rates, latencies, range_enabled, start_hovering); its
// components have their own loaders above. Not validated here (the rate checks need the other
// sections): the SitlRunner constructor validates the assembled struct.
void LoadParams(config::ParamReader& reader, SitlRunnerParams* params);

}  // namespace aperture::sim
