#pragma once
// The control policy of GapFlyt (Sanket et al., RA-L 2018, seed 002) Sec. III-B, the baseline of
// the moment servo: a PID on the error e between the safe point x_s and the projection of the
// body centre on the image, with forward motion set by a constant pitch theta_0.
//
//   e = x_s - x_B                      x_B: where the body's x axis pierces the image plane
//                                      (the direction the vehicle flies to), normalized coords
//   lateral  v = PID(e_x)  along the image x axis,  vertical  v = PID(e_y)  along image y,
//            both taken in the y_B-z_B plane (the paper varies roll for e_x, thrust for e_y)
//   forward  v_x = g tan(theta_0) / d_x,  the speed at which pitch theta_0 balances rotor drag
//            (Faessler thesis (F.2): 0 = g tan(theta_0) - d_x v_x in steady level flight).
//
// Adaptation: the paper's Bebop took roll, pitch and thrust; our flatness/position controller
// takes velocity references, so the PID output is the lateral/vertical velocity whose tracking
// sets roll and thrust, and theta_0 becomes the forward speed it holds. Yaw rate is 0 (the paper
// does not servo yaw). PID on the measurement as given (the paper smooths x_s upstream with a
// Kalman filter); the derivative is 0 on the first step; the integral is clamped so its term
// stays within max_speed_mps (anti-windup).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "servo/servo_step_result.h"

namespace aperture::servo {

struct PidServoParams {
  // Gains from normalized image error to velocity. e = 0.1 (a 0.3 m offset seen from 3 m) asks
  // for 0.25 m/s: the 3 m approach of the gapflyt scenario then aligns in ~1.2 s (the time
  // constant 3 m / kp), within the ~3 s the flight to the wall takes at theta_0 = 3 deg.
  double kp_mps = 2.5;   // [m/s per unit error]
  double ki_mps2 = 0.5;  // [m/s^2 per unit error]
  double kd_m = 0.2;     // [m per unit error rate]
  // Lateral and vertical speed limit, and the integral term's (anti-windup) [m/s].
  double max_speed_mps = 1.0;
  // theta_0 [deg]: "empirically chosen"; 3 deg holds ~1 m/s against d_x = 0.5 /s.
  double forward_pitch_deg = 3.0;
  // Throws std::invalid_argument naming the field: gains negative or not finite, speed limit not
  // positive, pitch outside [0, 30) deg.
  void Validate() const;
};

class PidServo {
 public:
  // T_BC: the camera mount (p_B = T_BC * p_C); the body's x axis must point into the camera's
  // half-space (z_C component > 0.1, so x_B has an image). rotor_drag_dx_per_s: d_x of (F.2)
  // (VehicleParameters::rotor_drag_D_per_s.x()), > 0 for a finite forward speed. Throws
  // std::invalid_argument otherwise or for invalid params.
  PidServo(const PidServoParams& params, const Eigen::Isometry3d& T_BC, double rotor_drag_dx_per_s);

  // One step at time t_s [s] (strictly increasing after Reset) with the safe point x_s in
  // normalized image coordinates. error = e = x_s - x_B (2 entries). Throws
  // std::invalid_argument for a non-finite x_s or time, or a time not after the previous one.
  ServoStepResult Step(double t_s, const Eigen::Vector2d& safe_point_n);
  // Forgets the integral and the previous error (a new approach).
  void Reset();

  // x_B: where the body's x axis pierces the normalized image plane.
  const Eigen::Vector2d& body_axis_n() const { return body_axis_n_; }
  double forward_speed_mps() const { return forward_speed_mps_; }
  const PidServoParams& params() const { return params_; }

 private:
  PidServoParams params_;
  Eigen::Isometry3d T_BC_;
  Eigen::Vector2d body_axis_n_;
  double forward_speed_mps_;
  // Unit directions in B of the image x and y axes, in the y_B-z_B plane.
  Eigen::Vector3d image_x_B_;
  Eigen::Vector3d image_y_B_;
  bool has_previous_ = false;
  double previous_t_s_ = 0.0;
  Eigen::Vector2d previous_error_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d integral_ = Eigen::Vector2d::Zero();  // [unit error * s]
};

}  // namespace aperture::servo
