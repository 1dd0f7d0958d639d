#include "planning/motion_primitive.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace aperture::planning {

MotionPrimitive::MotionPrimitive(const Eigen::Vector3d& p0_W, const Eigen::Vector3d& v0_W,
                                 const Eigen::Vector3d& a0_W, const Eigen::Vector3d& pf_W,
                                 const Eigen::Vector3d& vf_W, const Eigen::Vector3d& af_W,
                                 double duration_s, EndConstraint end_constraint)
    : p0_W_(p0_W), v0_W_(v0_W), a0_W_(a0_W), duration_s_(duration_s) {
  if (!(std::isfinite(duration_s) && duration_s > 0.0)) {
    throw std::invalid_argument("MotionPrimitive: duration_s = " + std::to_string(duration_s) +
                                " must be a positive finite number of seconds");
  }
  if (!(p0_W.allFinite() && v0_W.allFinite() && a0_W.allFinite() && pf_W.allFinite() &&
        vf_W.allFinite() && af_W.allFinite())) {
    throw std::invalid_argument(
        "MotionPrimitive: initial or final state has a non-finite component; pass finite "
        "positions, velocities and accelerations");
  }
  const double T = duration_s;
  const double T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T;
  const Eigen::Vector3d ds = pf_W - p0_W - v0_W * T - 0.5 * a0_W * T2;
  const Eigen::Vector3d dv = vf_W - v0_W - a0_W * T;
  const Eigen::Vector3d da = af_W - a0_W;
  switch (end_constraint) {
    case EndConstraint::kPositionVelocityAcceleration:  // the note's 3x3 matrix
      alpha_ = (720.0 * ds - 360.0 * T * dv + 60.0 * T2 * da) / T5;
      beta_ = (-360.0 * ds + 168.0 * T * dv - 24.0 * T2 * da) / T4;
      gamma_ = (60.0 * ds - 24.0 * T * dv + 3.0 * T2 * da) / T3;
      break;
    case EndConstraint::kPositionVelocity:  // + j(T) = 0
      alpha_ = (320.0 * ds - 120.0 * T * dv) / T5;
      beta_ = (-200.0 * ds + 72.0 * T * dv) / T4;
      gamma_ = (40.0 * ds - 12.0 * T * dv) / T3;
      break;
    case EndConstraint::kPositionAcceleration:  // + dj/dt(T) = 0
      alpha_ = (90.0 * ds - 15.0 * T2 * da) / (2.0 * T5);
      beta_ = (-90.0 * ds + 15.0 * T2 * da) / (2.0 * T4);
      gamma_ = (30.0 * ds - 3.0 * T2 * da) / (2.0 * T3);
      break;
    case EndConstraint::kPosition:  // + j(T) = dj/dt(T) = 0
      alpha_ = 20.0 * ds / T5;
      beta_ = -20.0 * ds / T4;
      gamma_ = 10.0 * ds / T3;
      break;
  }
}

Eigen::Vector3d MotionPrimitive::Position(double t) const {
  const double t2 = t * t, t3 = t2 * t;
  return p0_W_ + v0_W_ * t + a0_W_ * (t2 / 2.0) + gamma_ * (t3 / 6.0) + beta_ * (t3 * t / 24.0) +
         alpha_ * (t3 * t2 / 120.0);
}

Eigen::Vector3d MotionPrimitive::Velocity(double t) const {
  const double t2 = t * t, t3 = t2 * t;
  return v0_W_ + a0_W_ * t + gamma_ * (t2 / 2.0) + beta_ * (t3 / 6.0) + alpha_ * (t3 * t / 24.0);
}

Eigen::Vector3d MotionPrimitive::Acceleration(double t) const {
  const double t2 = t * t;
  return a0_W_ + gamma_ * t + beta_ * (t2 / 2.0) + alpha_ * (t2 * t / 6.0);
}

Eigen::Vector3d MotionPrimitive::Jerk(double t) const {
  return gamma_ + beta_ * t + alpha_ * (t * t / 2.0);
}

control::TrajectoryPoint MotionPrimitive::Sample(double t_s) const {
  control::TrajectoryPoint point;
  point.t_s = t_s;
  point.p_W = Position(t_s);
  point.v_W = Velocity(t_s);
  point.a_W = Acceleration(t_s);
  point.j_W = Jerk(t_s);
  point.s_W = Snap(t_s);
  return point;
}

Eigen::Vector3d MotionPrimitive::AxisCosts() const {
  const double T = duration_s_;
  const double T2 = T * T, T3 = T2 * T, T4 = T3 * T;
  const Eigen::Vector3d& a = alpha_;
  const Eigen::Vector3d& b = beta_;
  const Eigen::Vector3d& g = gamma_;
  return (g.array().square() + b.array() * g.array() * T +
          (b.array().square() + a.array() * g.array()) * (T2 / 3.0) +
          a.array() * b.array() * (T3 / 4.0) + a.array().square() * (T4 / 20.0))
      .matrix();
}

}  // namespace aperture::planning
