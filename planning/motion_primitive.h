#pragma once
// Minimum-jerk motion primitive of Mueller, Hehn & D'Andrea, "A computationally efficient motion
// primitive for quadrocopter trajectory generation" (T-RO 2015), as stated in the project note
// notes/motion_primitive.md. Each axis of W is an independent triple integrator; over the fixed
// duration T the primitive minimises J = (1/T) * integral_0^T |j(t)|^2 dt from the initial state
// (p0, v0, a0) to the end state. The optimal jerk of every axis is a quadratic in time,
//   j(t) = alpha t^2 / 2 + beta t + gamma,
// so position is a quintic. Time t is measured from the start of the primitive [s], 0 <= t <= T
// (evaluation outside that range extrapolates the polynomials). Units SI, frame W.
#include <Eigen/Core>

#include "control/trajectory_point.h"

namespace aperture::planning {

// Which end components are prescribed. Free components follow from the transversality conditions
// (their costate vanishes at T): a free end acceleration gives j(T) = 0, a free end velocity gives
// dj/dt(T) = 0. Closed forms derived with the same boundary conditions as the note's matrix.
enum class EndConstraint {
  kPositionVelocityAcceleration,  // the note's fully specified end state
  kPositionVelocity,              // end acceleration free
  kPositionAcceleration,          // end velocity free
  kPosition,                      // end velocity and acceleration free
};

class MotionPrimitive {
 public:
  // Rest at the origin for T = 1 s.
  MotionPrimitive() = default;

  // The primitive from (p0_W, v0_W, a0_W) at t = 0 to (pf_W, vf_W, af_W) at t = T. Components the
  // end constraint leaves free are ignored (pass anything finite). Throws std::invalid_argument
  // when duration_s is not a positive finite number or a state is not finite.
  MotionPrimitive(const Eigen::Vector3d& p0_W, const Eigen::Vector3d& v0_W,
                  const Eigen::Vector3d& a0_W, const Eigen::Vector3d& pf_W,
                  const Eigen::Vector3d& vf_W, const Eigen::Vector3d& af_W, double duration_s,
                  EndConstraint end_constraint = EndConstraint::kPositionVelocityAcceleration);

  double duration_s() const { return duration_s_; }
  // Coefficients of j(t) = alpha t^2/2 + beta t + gamma per axis.
  const Eigen::Vector3d& alpha() const { return alpha_; }
  const Eigen::Vector3d& beta() const { return beta_; }
  const Eigen::Vector3d& gamma() const { return gamma_; }
  const Eigen::Vector3d& initial_position_W() const { return p0_W_; }
  const Eigen::Vector3d& initial_velocity_W() const { return v0_W_; }
  const Eigen::Vector3d& initial_acceleration_W() const { return a0_W_; }

  Eigen::Vector3d Position(double t_s) const;
  Eigen::Vector3d Velocity(double t_s) const;
  Eigen::Vector3d Acceleration(double t_s) const;
  Eigen::Vector3d Jerk(double t_s) const;
  Eigen::Vector3d Snap(double t_s) const { return alpha_ * t_s + beta_; }
  // p, v, a, j, s at t (t_s = t); the heading fields stay zero (yaw is planned separately).
  control::TrajectoryPoint Sample(double t_s) const;

  // J = (1/T) int_0^T j_i(t)^2 dt of every axis (note: gamma^2 + beta gamma T + ...).
  Eigen::Vector3d AxisCosts() const;
  // Sum of AxisCosts(): the 3-D cost of the note.
  double Cost() const { return AxisCosts().sum(); }

 private:
  Eigen::Vector3d p0_W_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d v0_W_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d a0_W_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d alpha_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d beta_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gamma_ = Eigen::Vector3d::Zero();
  double duration_s_ = 1.0;
};

}  // namespace aperture::planning
