#pragma once
// Configuration descriptions (Serialize, config/param_archive.h) of the control parameter structs.
// Header-only templates over the archive (param_archive.h is header-only too): the control library
// neither includes this nor links config; the loaders and dumps are instantiated where a config
// archive is used (sim/, planning/).
//
//   vehicle: {mass_kg: 0.45, inertia_diag_kgm2: [0.001, 0.001, 0.002], arm_length_m: 0.178,
//             gravity_mps2: 9.81, rotor_drag_D_per_s: [0.5, 0.35, 0], rotor_drag_A: [[..]x3],
//             rotor_drag_B: [[..]x3], thrust_velocity_coeff_kh: 0, rotor_fitness: [1, 1, 1, 1],
//             rotor: {thrust_coeffs_N: [k0, k1, k2], torque_coeffs_Nm: [..],
//                     time_constant_up_s: 0.011, time_constant_down_s: 0.027,
//                     command_min: -1, command_max: 1}}
//   controller: {p_xy_per_s2: 5, p_z_per_s2: 15, d_xy_per_s: 4, d_z_per_s: 6,   # Table A.2,
//                p_rp_per_s: 16.6, p_yaw_per_s: 5, compensate_rotor_drag: true} # (F.31)-(F.38)
//   recovery: {max_tilt_for_height_rad: 0.349, max_roll_pitch_rate_radps: 10,   # B.3.2
//              max_vertical_speed_mps: 0.3, max_horizontal_speed_mps: 0.2,
//              min_height_filter_time_s: 0.3, controller: {..as above..}}
#include "config/param_archive.h"
#include "control/attitude_controller.h"
#include "control/lqr_body_rate_controller.h"
#include "control/position_controller.h"
#include "control/recovery_state_machine.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {

template <typename Archive>
void Serialize(Archive* a, RotorParameters* p) {
  a->Visit(APERTURE_NVP(p, thrust_coeffs_N));
  a->Visit(APERTURE_NVP(p, torque_coeffs_Nm));
  a->Visit(APERTURE_NVP(p, time_constant_up_s));
  a->Visit(APERTURE_NVP(p, time_constant_down_s));
  a->Visit(APERTURE_NVP(p, command_min));
  a->Visit(APERTURE_NVP(p, command_max));
}

template <typename Archive>
void Serialize(Archive* a, VehicleParameters* p) {
  a->Visit(APERTURE_NVP(p, mass_kg));
  a->Visit(APERTURE_NVP(p, inertia_diag_kgm2));
  a->Visit(APERTURE_NVP(p, arm_length_m));
  a->Visit(APERTURE_NVP(p, gravity_mps2));
  a->Visit(APERTURE_NVP(p, rotor_drag_D_per_s));
  a->Visit(APERTURE_NVP(p, rotor_drag_A));
  a->Visit(APERTURE_NVP(p, rotor_drag_B));
  a->Visit(APERTURE_NVP(p, thrust_velocity_coeff_kh));
  a->Visit(APERTURE_NVP(p, rotor_fitness));
  a->Visit(APERTURE_NVP(p, rotor));
}

// The gains of (F.31) and of the attitude controller, in one flat map.
template <typename Archive>
void SerializePositionGains(Archive* a, PositionControllerParams* p) {
  a->Visit(APERTURE_NVP(p, p_xy_per_s2));
  a->Visit(APERTURE_NVP(p, p_z_per_s2));
  a->Visit(APERTURE_NVP(p, d_xy_per_s));
  a->Visit(APERTURE_NVP(p, d_z_per_s));
  a->Visit(APERTURE_NVP(&p->attitude, p_rp_per_s));
  a->Visit(APERTURE_NVP(&p->attitude, p_yaw_per_s));
}

template <typename Archive>
void Serialize(Archive* a, PositionControllerParams* p) {
  SerializePositionGains(a, p);
  a->Visit(APERTURE_NVP(p, compensate_rotor_drag));
  a->Visit(APERTURE_NVP(p, compensate_rotor_lag));
}

template <typename Archive>
void Serialize(Archive* a, RecoveryParams* p) {
  a->Visit(APERTURE_NVP(p, max_tilt_for_height_rad));
  a->Visit(APERTURE_NVP(p, max_roll_pitch_rate_radps));
  a->Visit(APERTURE_NVP(p, max_vertical_speed_mps));
  a->Visit(APERTURE_NVP(p, max_horizontal_speed_mps));
  a->Visit(APERTURE_NVP(p, min_height_filter_time_s));
  a->Visit(APERTURE_NVP(p, controller));
}

template <typename Archive>
void Serialize(Archive* a, LqrBodyRateParameters* p) {
  a->Visit(APERTURE_NVP(p, state_weights));
  a->Visit(APERTURE_NVP(p, input_weights));
}

}  // namespace aperture::control
