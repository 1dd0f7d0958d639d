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

void PointServoParams::Validate() const {
  gain.Validate();
  if (!std::isfinite(target_motion_time_constant_s) || target_motion_time_constant_s < 0.0) {
    throw std::invalid_argument("PointServoParams.target_motion_time_constant_s = " +
                                std::to_string(target_motion_time_constant_s) +
                                " must be finite and >= 0 [s]");
  }
}

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
  has_previous_ = false;
  target_motion_.setZero();
}

ServoStepResult PointServo::Step(double t_s, const Corners& corners_n, double depth_m,
                                 const std::optional<BodyVelocityReference>& own_motion) {
  if (!has_desired()) {
    throw std::invalid_argument("PointServo::Step: no desired view; call SetDesired first");
  }
  RequireCorners(corners_n, "Step");
  RequireDepth(depth_m, "Step");
  if (!std::isfinite(t_s) || (has_previous_ && t_s <= previous_t_s_)) {
    throw std::invalid_argument("PointServo::Step: t_s = " + std::to_string(t_s) +
                                " must be finite and after the previous step's " +
                                std::to_string(previous_t_s_) + " [s]");
  }
  if (own_motion && (!own_motion->v_B.allFinite() || !std::isfinite(own_motion->yaw_rate_radps))) {
    throw std::invalid_argument("PointServo::Step: own_motion must be finite");
  }
  for (int i = 0; i < 4; ++i) {
    impl_->current[i].buildFrom(corners_n[i].x(), corners_n[i].y(), depth_m);
  }
  Eigen::VectorXd u = internal::ToEigen(impl_->task.computeControlLaw());  // -lambda J^+ e
  const Eigen::VectorXd error = internal::ToEigen(impl_->task.getError());
  if (params_.compensate_target_motion) {
    const Eigen::MatrixXd J = internal::ToEigen(impl_->task.getTaskJacobian());
    if (has_previous_) {
      const double dt_s = t_s - previous_t_s_;
      Eigen::VectorXd own = previous_u_;
      if (own_motion) {
        own << own_motion->v_B, own_motion->yaw_rate_radps;
      }
      const Eigen::VectorXd unexplained =
          (error - previous_error_) / dt_s - J * own;  // de/dt - J u: target's share
      const double blend = dt_s / (params_.target_motion_time_constant_s + dt_s);
      target_motion_ += blend * (unexplained - target_motion_);
    }
    u -= internal::ToEigen(impl_->task.getTaskJacobianPseudoInverse()) * target_motion_;
  }
  has_previous_ = true;
  previous_t_s_ = t_s;
  previous_error_ = error;
  previous_u_ = u;

  ServoStepResult result;
  result.reference.v_B = u.head<3>();
  result.reference.yaw_rate_radps = u[3];
  result.twist_C = CameraTwistFromBodyVelocity(result.reference, T_BC_);
  result.error = error;
  result.error_norm = error.norm();
  return result;
}

}  // namespace aperture::servo
