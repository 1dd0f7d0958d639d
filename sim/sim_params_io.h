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
//   quadratic_drag_per_m: 0.0       # effects the controllers do not model (0 = none)
//   drag_thrust_exponent: 0.0
//   battery_sag_per_s: 0.0
//
//   vehicle:                        # VehicleMismatchParams (sim/sitl/vehicle_mismatch.h)
//     mismatch: true                # the simulated vehicle is drawn per trial; false: = model
//     hover_thrust_calibration: true  # the flight controller knows the collective thrust scale
//     mismatch_bounds: {rotor_drag_relative: 0.2, thrust_velocity_coeff_kh_max: 0.02,
//                       quadratic_drag_max_per_m: 0.03, drag_thrust_exponent_max: 0.5,
//                       time_constant_relative: 0.3, thrust_map_relative: 0.3,
//                       torque_map_relative: 0.3, rotor_fitness_relative: 0.1,
//                       battery_sag_max_per_s: 0.001, esc_delay_max_s: 0.005,
//                       gyro_vibration_noise_max: 0.002, command_latency_s: [0.01, 0.015],
//                       estimate_latency_s: [0.01, 0.015]}
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
//          range_latency_s: 0, estimate_latency_s: 0, esc_delay_s: 0,            # fields only
//          range_enabled: true, start_hovering: true,
//          torque_observer_time_constant_s: 0.1}  # the flight controller's (0: the thesis' law)
//
// All throw std::invalid_argument naming where the bad value is and what is expected.
#include "config/yaml_read_archive.h"
#include "config/yaml_write_archive.h"
#include "control/control_params_io.h"
#include "control/vehicle_parameters.h"
#include "sim/sensors/imu_sensor.h"
#include "sim/sensors/odometry_sensor.h"
#include "sim/sensors/range_sensor.h"
#include "sim/sitl/collision_checker.h"
#include "sim/sitl/sitl_runner.h"
#include "sim/sitl/vehicle_mismatch.h"
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
  a->Visit(APERTURE_NVP(p, quadratic_drag_per_m));
  a->Visit(APERTURE_NVP(p, drag_thrust_exponent));
  a->Visit(APERTURE_NVP(p, battery_sag_per_s));
}

template <typename Archive>
void Serialize(Archive* a, VehicleMismatchBounds* p) {
  a->Visit(APERTURE_NVP(p, rotor_drag_relative));
  a->Visit(APERTURE_NVP(p, thrust_velocity_coeff_kh_max));
  a->Visit(APERTURE_NVP(p, quadratic_drag_max_per_m));
  a->Visit(APERTURE_NVP(p, drag_thrust_exponent_max));
  a->Visit(APERTURE_NVP(p, time_constant_relative));
  a->Visit(APERTURE_NVP(p, thrust_map_relative));
  a->Visit(APERTURE_NVP(p, torque_map_relative));
  a->Visit(APERTURE_NVP(p, rotor_fitness_relative));
  a->Visit(APERTURE_NVP(p, battery_sag_max_per_s));
  a->Visit(APERTURE_NVP(p, esc_delay_max_s));
  a->Visit(APERTURE_NVP(p, gyro_vibration_noise_max));
  a->Visit(APERTURE_NVP(p, command_latency_s));
  a->Visit(APERTURE_NVP(p, estimate_latency_s));
}

template <typename Archive>
void Serialize(Archive* a, VehicleMismatchParams* p) {
  a->Visit(APERTURE_NVP(p, mismatch));
  a->Visit(APERTURE_NVP(p, mismatch_bounds));
  a->Visit(APERTURE_NVP(p, hover_thrust_calibration));
}

// A drawn vehicle (for reports: DumpParams).
template <typename Archive>
void Serialize(Archive* a, VehicleMismatch* p) {
  a->Visit(APERTURE_NVP(p, rotor_drag_factor_xy));
  a->Visit(APERTURE_NVP(p, thrust_velocity_coeff_kh));
  a->Visit(APERTURE_NVP(p, quadratic_drag_per_m));
  a->Visit(APERTURE_NVP(p, drag_thrust_exponent));
  a->Visit(APERTURE_NVP(p, time_constant_up_factor));
  a->Visit(APERTURE_NVP(p, time_constant_down_factor));
  a->Visit(APERTURE_NVP(p, thrust_map_factor));
  a->Visit(APERTURE_NVP(p, torque_map_factor));
  a->Visit(APERTURE_NVP(p, rotor_fitness_factor));
  a->Visit(APERTURE_NVP(p, battery_sag_per_s));
  a->Visit(APERTURE_NVP(p, esc_delay_s));
  a->Visit(APERTURE_NVP(p, gyro_vibration_noise));
  a->Visit(APERTURE_NVP(p, command_latency_s));
  a->Visit(APERTURE_NVP(p, estimate_latency_s));
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

// OdometrySensorParams (the seed is the caller's: the forest flight derives it from the
// scenario's).
template <typename Archive>
void Serialize(Archive* a, OdometrySensorParams* p) {
  a->Visit(APERTURE_NVP(p, rate_hz));
  a->Visit(APERTURE_NVP(p, position_sigma_m));
  a->Visit(APERTURE_NVP(p, rotation_sigma_rad));
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

// The loop fields of SitlRunnerParams only (rates, latencies, range_enabled, start_hovering, the
// flight controller's torque observer); its components have their own descriptions above.
template <typename Archive>
void Serialize(Archive* a, SitlRunnerParams* p) {
  a->Visit(APERTURE_NVP(p, dynamics_rate_hz));
  a->Visit(APERTURE_NVP(p, control_rate_hz));
  a->Visit(APERTURE_NVP(p, command_latency_s));
  a->Visit(APERTURE_NVP(p, range_latency_s));
  a->Visit(APERTURE_NVP(p, estimate_latency_s));
  a->Visit(APERTURE_NVP(p, esc_delay_s));
  a->Visit(APERTURE_NVP(p, range_enabled));
  a->Visit(APERTURE_NVP(p, start_hovering));
  a->Visit("torque_observer_time_constant_s",
           &p->flight_controller.low_level.torque_observer_time_constant_s);
}
// Only the torque observer is validated when loaded: the rate checks compare against the IMU,
// range and flight-controller rates, which other sections set; SitlRunner validates the assembled
// struct.
inline void ValidateParams(const SitlRunnerParams& p) { p.flight_controller.low_level.Validate(); }

}  // namespace aperture::sim
