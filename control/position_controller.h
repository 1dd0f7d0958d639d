#pragma once
// High-level position controller with differential-flatness feed-forward, Faessler thesis
// (F.31)-(F.38), with the attitude controller of paper B (B.10)-(B.20) for omega_fb (F.37):
//
//   a_des = -K_pos (p - p_ref) - K_vel (v - v_ref) + a_ref + R_ref D R_ref^T v_ref + g z_W
//                                                                       (F.31), (F.32)
//   z_des = a_des / |a_des|, R_des from z_des and psi_ref               (F.33)-(F.35)
//   c_cmd = a_des^T z_B - k_h (v^T (x_B + y_B))^2, current x_B, y_B, z_B (F.36)
//           [+ tau c_dot_ref with compensate_rotor_lag]
//   omega_des = omega_fb + omega_ref, omega_dot_des = omega_dot_ref     (F.37), (F.38)
// where R_ref, omega_ref, omega_dot_ref come from ComputeFlatnessOutputs on the reference.
//
// Gains: F writes the feedback with constant diagonal K_pos, K_vel (F.32) and takes omega_fb
// from the attitude controller of [37] = paper B; paper B's position controller (B.8) has exactly
// that structure with P_pos = diag(p_xy, p_xy, p_z), D_pos = diag(d_xy, d_xy, d_z). F gives no
// gain values, so the defaults are those of Table A.2 (paper A's platform, same controller).
//
// Drag compensation switch: when off, the controller's model has D = 0 and k_h = 0 (the drag
// terms of F.31, F.36 and of the feed-forward vanish: the classic controller of paper B plus
// feed-forward); A and B do not enter the command [c_cmd, omega] at all.
//
// At zero tracking error (state = flatness state of the reference) the command equals the
// flatness outputs: c_cmd = c_cmd,ref, omega_des = omega_ref, omega_dot_des = omega_dot_ref.
// If |a_des| < kMinThrust_mps2 (commanded free fall) the thrust direction is undefined: z_des is
// the current z_B (no roll/pitch feedback) and thrust_direction_defined is false.
#include <Eigen/Core>

#include "control/attitude_controller.h"
#include "control/commands.h"
#include "control/flatness.h"
#include "control/quad_state.h"
#include "control/trajectory_point.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {

struct PositionControllerParams {
  double p_xy_per_s2 = 5.0;           // horizontal position gain (Table A.2)
  double p_z_per_s2 = 15.0;           // vertical position gain (Table A.2)
  double d_xy_per_s = 4.0;            // horizontal velocity gain (Table A.2)
  double d_z_per_s = 6.0;             // vertical velocity gain (Table A.2)
  AttitudeControllerGains attitude;   // p_rp = 16.6, p_yaw = 5 (Table A.2)
  bool compensate_rotor_drag = true;  // false: D and k_h treated as zero (F.7.4 "not cons. drag")
  // Feed-forward of the rotors' first-order lag (alpha_up/alpha_dwn of G.6.1) on the collective
  // thrust: c_cmd + tau c_dot_ref (F.29), tau the rising or falling time constant, so that a
  // lagging rotor delivers c_ref on a thrust ramp instead of c_ref - tau c_dot_ref. Beyond F;
  // off by default (a ramp of c from 20 to 5 m/s^2 in 0.25 s otherwise leaves ~1.6 m/s^2 of
  // excess thrust at the 27 ms falling time constant).
  bool compensate_rotor_lag = false;
  // Throws std::invalid_argument naming the gain when one is negative or not finite.
  void Validate() const;
};

struct PositionControllerOutput {
  ThrustRatesCommand command;                         // c_cmd, omega_des, omega_dot_des
  Eigen::Vector3d a_des_W = Eigen::Vector3d::Zero();  // (F.31) [m/s^2]
  AttitudeFeedback attitude;                          // R_des, omega_fb, tilt error
  FlatnessResult reference;                           // feed-forward terms (F.37, F.38)
  bool thrust_direction_defined = true;
};

class PositionController {
 public:
  // `vehicle` supplies g, D, k_h (and J, A, B for the reference torque); validated.
  explicit PositionController(const VehicleParameters& vehicle,
                              const PositionControllerParams& params = {});
  // Throws std::invalid_argument when the state is invalid (QuadState::IsValid) or the reference
  // is not finite.
  PositionControllerOutput Compute(const QuadState& state, const TrajectoryPoint& reference) const;

  const PositionControllerParams& params() const { return params_; }
  // The vehicle model used by the controller (drag terms zeroed when compensation is off).
  const VehicleParameters& model() const { return model_; }

 private:
  PositionControllerParams params_;
  VehicleParameters model_;
  AttitudeController attitude_controller_;
};

}  // namespace aperture::control
