#pragma once
// The servo of the GapFlyt flight (issue 14): one interface over the two laws that fly the
// vehicle at the tracked opening, selected by `servo.law`:
//
//   moments  MomentServo (servo/moment_servo.h) on the opening's contour: centre, area and (for a
//            downward camera) orientation to a desired view;
//   pid      PidServo (servo/pid_servo.h), the paper's policy (Sec. III-B) on the safe point x_s.
//
// Each step takes one OpeningView (both inputs; each law reads its own) and returns the body
// velocity reference for the flatness/position controller.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "servo/moment_servo.h"
#include "servo/pid_servo.h"
#include "servo/servo_step_result.h"

namespace aperture::servo {

enum class GapServoLaw { kMoments, kPid };
// "moments", "pid".
const char* ToString(GapServoLaw law);

struct GapServoParams {
  // The moment servo is the law; the PID is the paper's baseline to compare against.
  GapServoLaw law = GapServoLaw::kMoments;
  MomentServoParams moments;  // yaw = hold: GapFlyt's camera looks forward
  PidServoParams pid;
  // Throws std::invalid_argument naming the field (through the laws' Validate()).
  void Validate() const;
};

// One tracked view of the opening, both in normalized image coordinates (x right, y down).
struct OpeningView {
  double t_s = 0.0;                                        // image time [s]
  std::vector<Eigen::Vector2d> contour_n;                  // the opening's polygon (moments)
  Eigen::Vector2d safe_point_n = Eigen::Vector2d::Zero();  // x_s (pid)
};

class GapServo {
 public:
  // T_BC: the forward camera's mount; rotor_drag_dx_per_s: d_x of the vehicle (PID's forward
  // speed). Throws std::invalid_argument for invalid params or a mount the law cannot use.
  GapServo(const GapServoParams& params, const Eigen::Isometry3d& T_BC, double rotor_drag_dx_per_s);

  // The goal view for the moment law (see MomentServo::SetDesired); ignored by the PID.
  void SetDesired(const std::vector<Eigen::Vector2d>& contour_n, double depth_m);
  // One step of the selected law; throws what that law's Step throws.
  ServoStepResult Step(const OpeningView& view);

  GapServoLaw law() const { return params_.law; }

 private:
  GapServoParams params_;
  std::unique_ptr<MomentServo> moments_;  // set when law == kMoments
  std::unique_ptr<PidServo> pid_;         // set when law == kPid
};

}  // namespace aperture::servo
