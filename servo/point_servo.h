#pragma once
// Image-based visual servo on four points (the corners of a tag), the classical IBVS law of
// Chaumette & Hutchinson, "Visual servo control, Part I", IEEE RAM 2006, Sec. "Image-based
// visual servo" (vpFeaturePoint with vpServo), in the 4-DOF drone form of MomentServo
// (servo/moment_servo.h):
//
//   s = [x_1, y_1, .., x_4, y_4] (normalized image coordinates, x right, y down),
//   L_i = [-1/Z, 0, x/Z, xy, -(1+x^2), y; 0, -1/Z, y/Z, 1+y^2, -xy, -x]   (the paper's L_x),
//   u = [v_B; yaw rate] = -lambda (L_s cVe eJe)^+ (s - s*),
//
// with Z the current depth of the points (the tag plane's distance along the optical axis; an
// estimate such as the range sensor's height is enough, the law tolerates depth errors, as the
// paper discusses for approximate interaction matrices). The four corners fix all four DOFs for any
// mount; with a downward camera above a tag on the ground (issue 16's tag servo) x/y move the
// vehicle horizontally, the corners' rotation turns it and their spread sets the height.
//
// A moving target (issue 16: the ground robot drives at 0.3 m/s) leaves the proportional law a
// steady lag e = -lambda^-1 de/dt|_target. With compensate_target_motion the law adds the
// feed-forward of Chaumette & Hutchinson 2006 (Part I, Sec. "Target tracking"):
//   u = -lambda J^+ e - J^+ (de/dt)^,  J = L_s cVe eJe,
//   (de/dt)^ = low-pass[(e_k - e_k-1) / dt - J u_k-1]   (the feature motion the own motion did
//                                                          not explain), time constant
//                                                          target_motion_time_constant_s.
//
// Corners correspond by index between SetDesired and Step.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <optional>

#include "servo/servo_gain.h"
#include "servo/servo_step_result.h"

namespace aperture::servo {

struct PointServoParams {
  ServoGain gain;
  bool compensate_target_motion = true;
  // Low-pass on the target-motion estimate [s]: 0.2 s spans 6 frames at 30 Hz (corner noise of
  // ~0.5 px is averaged) and stays short against a ground robot's speed changes (~1 s).
  double target_motion_time_constant_s = 0.2;
  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

class PointServo {
 public:
  using Corners = std::array<Eigen::Vector2d, 4>;

  // T_BC: the camera mount (p_B = T_BC * p_C). Throws std::invalid_argument for invalid params
  // or a non-rigid mount.
  PointServo(const PointServoParams& params, const Eigen::Isometry3d& T_BC);
  ~PointServo();
  PointServo(const PointServo&) = delete;
  PointServo& operator=(const PointServo&) = delete;

  // The corners as seen from the goal pose, at depth depth_m [m]. Throws std::invalid_argument
  // for non-finite corners, coincident corners, or a depth <= 0.
  void SetDesired(const Corners& corners_n, double depth_m);
  bool has_desired() const;

  // One servo step at the image time t_s [s] (increasing); depth_m the current depth estimate
  // [m]. error = s - s* (8 entries, corner by corner x then y). Throws std::invalid_argument
  // before SetDesired, for non-finite corners or time, a depth <= 0 or a time not after the
  // previous step's.
  // own_motion: the vehicle's measured body velocity and yaw rate since the previous step (its
  // state estimate); the target-motion estimate then subtracts what the vehicle really did rather
  // than what the previous step commanded (a vehicle whose velocity loop lags or rate-limits the
  // reference).
  ServoStepResult Step(double t_s, const Corners& corners_n, double depth_m,
                       const std::optional<BodyVelocityReference>& own_motion = std::nullopt);
  // The current target-motion estimate (de/dt)^ (8 entries; zero without compensation).
  const Eigen::VectorXd& target_motion() const { return target_motion_; }

  const PointServoParams& params() const { return params_; }

 private:
  struct Impl;  // ViSP point features and task
  PointServoParams params_;
  Eigen::Isometry3d T_BC_;
  std::unique_ptr<Impl> impl_;
  bool has_previous_ = false;
  double previous_t_s_ = 0.0;
  Eigen::VectorXd previous_error_;
  Eigen::VectorXd previous_u_;  // [v_B; yaw rate] commanded at the previous step
  Eigen::VectorXd target_motion_ = Eigen::VectorXd::Zero(8);
};

}  // namespace aperture::servo
