#include "servo/point_servo.h"

#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/vs/vpServo.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "servo/internal/visp_conversions.h"

namespace aperture::servo {
namespace {

void RequireCorners(const PointServo::Corners& corners_n, const char* what) {
  for (const Eigen::Vector2d& corner : corners_n) {
    if (!corner.allFinite()) {
      throw std::invalid_argument(std::string("PointServo::") + what +
                                  ": a corner is not finite; pass normalized image coordinates");
    }
  }
}

void RequireDepth(double depth_m, const char* what) {
  if (!std::isfinite(depth_m) || depth_m <= 0.0) {
    throw std::invalid_argument(std::string("PointServo::") + what +
                                ": depth_m = " + std::to_string(depth_m) +
                                " must be finite and > 0 (distance of the tag plane along the "
                                "optical axis) [m]");
  }
}

}  // namespace

struct PointServo::Impl {
  std::array<vpFeaturePoint, 4> current;
  std::array<vpFeaturePoint, 4> desired;
  vpServo task;
};

PointServo::PointServo(const PointServoParams& params, const Eigen::Isometry3d& T_BC)
    : params_(params), T_BC_(T_BC) {
  params_.Validate();
  RequireRigidMount(T_BC, "PointServo");
}

PointServo::~PointServo() = default;

bool PointServo::has_desired() const { return impl_ != nullptr; }

void PointServo::SetDesired(const Corners& corners_n, double depth_m) {
  RequireCorners(corners_n, "SetDesired");
  RequireDepth(depth_m, "SetDesired");
  // Coincident corners (closer than 1e-6, ~1/2000 px at f = 500 px) make two rows of L_s equal.
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      if ((corners_n[i] - corners_n[j]).norm() < 1e-6) {
        throw std::invalid_argument("PointServo::SetDesired: corners " + std::to_string(i) +
                                    " and " + std::to_string(j) +
                                    " coincide; pass four distinct corners");
      }
    }
  }
  auto impl = std::make_unique<Impl>();
  internal::ConfigureDroneTask(params_.gain, T_BC_, /*with_yaw_rate=*/true, &impl->task);
  for (int i = 0; i < 4; ++i) {
    impl->desired[i].buildFrom(corners_n[i].x(), corners_n[i].y(), depth_m);
    impl->current[i].buildFrom(corners_n[i].x(), corners_n[i].y(), depth_m);
    impl->task.addFeature(impl->current[i], impl->desired[i]);
  }
  impl_ = std::move(impl);
}

ServoStepResult PointServo::Step(const Corners& corners_n, double depth_m) {
  if (!has_desired()) {
    throw std::invalid_argument("PointServo::Step: no desired view; call SetDesired first");
  }
  RequireCorners(corners_n, "Step");
  RequireDepth(depth_m, "Step");
  for (int i = 0; i < 4; ++i) {
    impl_->current[i].buildFrom(corners_n[i].x(), corners_n[i].y(), depth_m);
  }
  ServoStepResult result;
  const vpColVector u = impl_->task.computeControlLaw();
  internal::FillReference(u, T_BC_, &result.reference, &result.twist_C);
  result.error = internal::ToEigen(impl_->task.getError());
  result.error_norm = result.error.norm();
  return result;
}

}  // namespace aperture::servo
