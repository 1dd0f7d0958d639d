#pragma once
// Configuration descriptions (Serialize, config/param_archive.h) of the simulated vehicle, its
// disturbances and sensors: LoadParams(reader, &params) loads (config/yaml_read_archive.h),
// config::DumpParams dumps. Keys are the struct field names (they carry their units); absent keys
// keep the in-class defaults; unknown keys are rejected with the file, line and the list of known
// keys. Loading ends with the struct's Validate(), so a loaded struct is always usable.
//
//   vehicle:                        # control::VehicleParameters (control/control_params_io.h)
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
//     pushes: [[t_s, J_x, J_y, J_z], [t_s, J_x, J_y, J_z, L_x, L_y, L_z]]  # J in W, L in B
//     torque_B_Nm: [0, 0, 0]   # constant torque in B [N m]; pushes: J [N s], L [N m s]
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
#include "config/yaml_read_archive.h"
#include "config/yaml_write_archive.h"
#include "control/control_params_io.h"
#include "control/vehicle_parameters.h"
#include "sim/sensors/imu_sensor.h"
#include "sim/sensors/range_sensor.h"
#include "sim/sitl/collision_checker.h"
#include "sim/sitl/sitl_runner.h"
#include "sim/vehicle/disturbances.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::sim {

template <typename Archive>
void Serialize(Archive* a, QuadrotorDynamicsParams* p) {
  a->Visit(APERTURE_NVP(p, vehicle));
  a->Visit(APERTURE_NVP(p, max_integration_step_s));
  a->Visit(APERTURE_NVP(p, rotor_lag_enabled));
  a->Visit(APERTURE_NVP(p, ground_contact_enabled));
  a->Visit(APERTURE_NVP(p, ground_height_m));
  a->Visit(APERTURE_NVP(p, landing_gear_height_m));
}

// Leaf formats: a gust as [t_start_s, duration_s, wind_x, wind_y, wind_z], a push as
// [t_s, J_x, J_y, J_z] or [t_s, J_x, J_y, J_z, L_x, L_y, L_z] (the short form when L = 0).
void ConvertNode(const YAML::Node& node, const config::ValueContext& context, WindGust* gust);
void ConvertNode(const YAML::Node& node, const config::ValueContext& context, Push* push);
YAML::Node EncodeNode(const WindGust& gust);
YAML::Node EncodeNode(const Push& push);

template <typename Archive>
void Serialize(Archive* a, DisturbanceParams* p) {
  a->Visit(APERTURE_NVP(p, steady_wind_W_mps));
  a->Visit(APERTURE_NVP(p, gusts));
  a->Visit(APERTURE_NVP(p, pushes));
  a->Visit(APERTURE_NVP(p, torque_B_Nm));
}

template <typename Archive>
void Serialize(Archive* a, ImuSensorParams* p) {
  a->Visit(APERTURE_NVP(p, rate_hz));
  a->Visit(APERTURE_NVP(p, latency_s));
  a->Visit(APERTURE_NVP(p, stamp_at_delivery));
  a->Visit(APERTURE_NVP(p, accel_noise_density));
  a->Visit(APERTURE_NVP(p, gyro_noise_density));
  a->Visit(APERTURE_NVP(p, accel_bias_random_walk));
  a->Visit(APERTURE_NVP(p, gyro_bias_random_walk));
  a->Visit(APERTURE_NVP(p, accel_bias_initial_B));
  a->Visit(APERTURE_NVP(p, gyro_bias_initial_B));
  a->Visit(APERTURE_NVP(p, seed));
}

template <typename Archive>
void Serialize(Archive* a, RangeSensorParams* p) {
  a->Visit(APERTURE_NVP(p, rate_hz));
  a->Visit(APERTURE_NVP(p, min_range_m));
  a->Visit(APERTURE_NVP(p, max_range_m));
  a->Visit(APERTURE_NVP(p, noise_sigma_m));
  a->Visit(APERTURE_NVP(p, max_tilt_rad));
  a->Visit(APERTURE_NVP(p, p_BS));
  a->Visit(APERTURE_NVP(p, seed));
}

template <typename Archive>
void Serialize(Archive* a, CollisionParams* p) {
  a->Visit(APERTURE_NVP(p, body_radius_m));
  a->Visit(APERTURE_NVP(p, propeller_radius_m));
  a->Visit(APERTURE_NVP(p, ground_enabled));
  a->Visit(APERTURE_NVP(p, max_touchdown_speed_mps));
  a->Visit(APERTURE_NVP(p, max_touchdown_tilt_rad));
  a->Visit(APERTURE_NVP(p, ignored_objects));
  a->Visit(APERTURE_NVP(p, sphere_rays));
  a->Visit(APERTURE_NVP(p, disk_rays));
}

// The loop fields of SitlRunnerParams only (rates, latencies, range_enabled, start_hovering); its
// components have their own descriptions above.
template <typename Archive>
void Serialize(Archive* a, SitlRunnerParams* p) {
  a->Visit(APERTURE_NVP(p, dynamics_rate_hz));
  a->Visit(APERTURE_NVP(p, control_rate_hz));
  a->Visit(APERTURE_NVP(p, command_latency_s));
  a->Visit(APERTURE_NVP(p, range_latency_s));
  a->Visit(APERTURE_NVP(p, range_enabled));
  a->Visit(APERTURE_NVP(p, start_hovering));
}
// Not validated when loaded: the rate checks compare against the IMU, range and flight-controller
// rates, which other sections set; SitlRunner validates the assembled struct.
inline void ValidateParams(const SitlRunnerParams& /*loop_fields_only*/) {}

}  // namespace aperture::sim
