#pragma once
// Image-based visual servo on four points (the corners of a tag), the classical IBVS law of
// Chaumette & Hutchinson, IEEE RAM 2006, eq. (11)-(12) (vpFeaturePoint with vpServo), in the
// 4-DOF drone form of MomentServo (servo/moment_servo.h):
//
//   s = [x_1, y_1, .., x_4, y_4] (normalized image coordinates, x right, y down),
//   L_i = [-1/Z, 0, x/Z, xy, -(1+x^2), y; 0, -1/Z, y/Z, 1+y^2, -xy, -x]   (eq. (11)),
//   u = [v_B; yaw rate] = -lambda (L_s cVe eJe)^+ (s - s*),
//
// with Z the current depth of the points (the tag plane's distance along the optical axis; an
// estimate such as the range sensor's height is enough, the law tolerates depth errors, Sec.
// IV-B of the paper). The four corners fix all four DOFs for any mount; with a downward camera
// above a tag on the ground (issue 16's tag servo) x/y move the vehicle horizontally, the
// corners' rotation turns it and their spread sets the height.
//
// Corners correspond by index between SetDesired and Step.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>

#include "servo/servo_gain.h"
#include "servo/servo_step_result.h"

namespace aperture::servo {

struct PointServoParams {
  ServoGain gain;
  // Throws std::invalid_argument naming the field.
  void Validate() const { gain.Validate(); }
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

  // One servo step; depth_m the current depth estimate [m]. error = s - s* (8 entries, corner
  // by corner x then y). Throws std::invalid_argument before SetDesired, for non-finite corners
  // or a depth <= 0.
  ServoStepResult Step(const Corners& corners_n, double depth_m);

  const PointServoParams& params() const { return params_; }

 private:
  struct Impl;  // ViSP point features and task
  PointServoParams params_;
  Eigen::Isometry3d T_BC_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aperture::servo
