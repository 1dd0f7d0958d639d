#include "servo/gap_servo.h"

namespace aperture::servo {

const char* ToString(GapServoLaw law) {
  switch (law) {
    case GapServoLaw::kMoments:
      return "moments";
    case GapServoLaw::kPid:
      return "pid";
  }
  return "unknown";
}

void GapServoParams::Validate() const {
  moments.Validate();
  pid.Validate();
}

GapServo::GapServo(const GapServoParams& params, const Eigen::Isometry3d& T_BC,
                   double rotor_drag_dx_per_s)
    : params_(params) {
  params_.Validate();
  if (params_.law == GapServoLaw::kMoments) {
    moments_ = std::make_unique<MomentServo>(params_.moments, T_BC);
  } else {
    pid_ = std::make_unique<PidServo>(params_.pid, T_BC, rotor_drag_dx_per_s);
  }
}

void GapServo::SetDesired(const std::vector<Eigen::Vector2d>& contour_n, double depth_m) {
  if (moments_) moments_->SetDesired(contour_n, depth_m);
}

ServoStepResult GapServo::Step(const OpeningView& view) {
  if (moments_) return moments_->Step(view.contour_n);
  return pid_->Step(view.t_s, view.safe_point_n);
}

}  // namespace aperture::servo
