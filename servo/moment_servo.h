#pragma once
// Image-moment visual servo on a planar polygon (the opening's contour, the tag's outline), after
// Tahri & Chaumette, "Point-based and region-based image moments for visual servoing of planar
// objects", IEEE T-RO 2005, in the 4-DOF form ViSP uses for drones (vpServo
// EYEINHAND_L_cVe_eJe, as in its Bebop 2 and Pixhawk servo examples):
//
//   features  s = [x_n, y_n, a_n (, alpha)]   (T-RO 2005; vpFeatureMoment* in ViSP):
//             a_n = Z* sqrt(a*/a)  normalized area (a image area, a*, Z* of the desired view),
//             x_n = a_n x_g, y_n = a_n y_g  normalized centre of gravity,
//             alpha = 1/2 atan2(2 mu11, mu20 - mu02)  orientation (third-order moments of the
//             desired view resolve it to [-pi, pi]).
//   law       u = -lambda (L_s cVe eJe)^+ (s - s*),  u = [v_B; yaw rate] or v_B (yaw hold),
//             L_s the interaction matrix at the current features on the plane 1/Z = 1/Z*
//             (target assumed parallel to the image plane, A = B = 0), cVe the velocity twist
//             matrix of T_CB (ViSP's cMe), eJe the selection of the commanded body DOFs.
//
// For a target parallel to the image plane the translational rows of x_n, y_n, a_n are -I: the
// error decays exponentially in translation, independently of the depth (the point of the
// normalization in the paper). alpha is the rotation about the optical axis, so it observes yaw
// only when the optical axis is along z_B (a downward camera); for a forward camera the yaw DOF is
// held (YawMode::kHold) and x_n, y_n, a_n drive v_B alone. Choosing kOrientation with a forward
// camera is rejected.
//
// Input: the polygon's vertices in normalized image coordinates (x = X/Z, y = Y/Z in C: x right,
// y down), in order around the contour (either direction). ViSP types stay in the .cc file.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "servo/servo_gain.h"
#include "servo/servo_step_result.h"

namespace aperture::servo {

enum class YawMode {
  kHold,         // yaw rate 0; features x_n, y_n, a_n; u = v_B (3 DOF)
  kOrientation,  // yaw from alpha; features x_n, y_n, a_n, alpha; u = [v_B; yaw rate] (4 DOF)
};

struct MomentServoParams {
  ServoGain gain;
  YawMode yaw = YawMode::kHold;  // the forward camera of GapFlyt; kOrientation for a downward one
  // A polygon whose image area is below this [normalized units^2] gives kDegenerateFeatures:
  // 1e-6 is a 0.5 px square at f = 500 px, where the contour's own noise dominates.
  double min_area_n2 = 1e-6;
  // alpha is undefined when the second moments are isotropic ((mu20 - mu02)^2 + 4 mu11^2 ~ 0, a
  // square or a regular polygon): below this fraction of (mu20 + mu02)^2 the orientation counts
  // as undefined (0.01 = axes of inertia differing by ~10 %).
  double min_orientation_anisotropy = 0.01;
  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

class MomentServo {
 public:
  // T_BC: the camera mount (p_B = T_BC * p_C). Throws std::invalid_argument for invalid params,
  // a non-rigid mount, or YawMode::kOrientation with an optical axis more than 60 deg off z_B
  // (alpha would observe roll, not yaw).
  MomentServo(const MomentServoParams& params, const Eigen::Isometry3d& T_BC);
  ~MomentServo();
  MomentServo(const MomentServo&) = delete;
  MomentServo& operator=(const MomentServo&) = delete;

  // The desired view: the polygon as seen from the goal pose, whose plane is depth_m [m] in
  // front of the camera. Throws std::invalid_argument for fewer than 3 vertices, non-finite
  // coordinates, a depth <= 0, a polygon below min_area_n2, or (kOrientation) a polygon whose
  // orientation is undefined.
  void SetDesired(const std::vector<Eigen::Vector2d>& polygon_n, double depth_m);
  bool has_desired() const;

  // One servo step on the current view of the same polygon (vertices need not correspond to the
  // desired ones). error = [x_n, y_n, a_n (, alpha)] - s*; alpha error wrapped to [-pi, pi].
  // Throws std::invalid_argument before SetDesired, for fewer than 3 vertices or non-finite ones.
  ServoStepResult Step(const std::vector<Eigen::Vector2d>& polygon_n);

  const MomentServoParams& params() const { return params_; }
  const Eigen::Isometry3d& T_BC() const { return T_BC_; }

 private:
  struct Impl;  // ViSP moment databases, features and task
  MomentServoParams params_;
  Eigen::Isometry3d T_BC_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aperture::servo
