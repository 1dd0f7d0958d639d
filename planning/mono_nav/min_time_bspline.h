#pragma once
// Minimum-time quintic B-spline through a path under velocity, acceleration and jerk limits
// (seed 003 Sec. III-E):
//  1. a quintic B-spline s(u), u in [0, 1], interpolates the path points q_0..q_n at chord-length
//     parameters u_i (The NURBS Book global interpolation);
//  2. time scaling t = lambda_i u on every interval [u_i, u_i+1] (16)-(17): with chi_i =
//  1/lambda_i,
//       v = s'(u) chi_i,  a = s''(u) chi_i^2,  j = s'''(u) chi_i^3            (18)-(20)
//     and the optimisation (21)-(32), sampled at samples_per_interval + 1 points per interval:
//       min_chi  sum (|s'(u)| chi_i - v_max)^2
//       s.t.     |s'(u)| chi_i <= v_max,  |s''_l(u)| chi_i^2 <= a_max,l,  |s'''_l(u)| chi_i^3 <=
//       j_max,l
//     solved with NLopt (SLSQP); then t_i+1 = t_i + (u_i+1 - u_i) / chi_i;
//  3. the least-squares control-point refit (33) that removes the velocity/acceleration/jerk jumps
//     the independent chi_i leave at the interval joints: a quintic B-spline in time fitted to the
//     time-scaled samples, with the end positions, velocities and accelerations as equality
//     constraints (Aeq xi = beq);
//  4. because the refit can overshoot a limit between the optimised samples, the refit is repeated
//     on times stretched by R = max(v/v_max, sqrt(a/a_max), cbrt(j/j_max)) over dense samples until
//     R = 1 within saturation_tolerance (with rest at both ends one uniform stretch is exact). The
//     result respects every limit at every dense sample and saturates the binding one (the paper's
//     time-optimality check: at least one of the limits is reached).
// Frame: any fixed frame (W); units SI.
#include <Eigen/Core>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "planning/mono_nav/bspline.h"

namespace aperture::planning {

struct DynamicLimits {
  double max_speed_mps = 1.3;  // paper Fig. 6
  Eigen::Vector3d max_acceleration_mps2 = Eigen::Vector3d::Constant(0.5);
  Eigen::Vector3d max_jerk_mps3 = Eigen::Vector3d::Constant(0.5);

  // Per-axis jerk bound of Sec. III-E d): j_max,l = f_min omega_max / sqrt(3), from the minimum
  // mass-normalised collective thrust f_min [m/s^2] and the maximum body rate omega_max [rad/s]
  // (Mueller & D'Andrea [6]: |j| <= f omega for a rigid quadrotor).
  static double JerkBound(double min_thrust_mps2, double max_body_rate_radps);

  void Validate() const;  // std::invalid_argument naming the field
};

struct MinTimeBSplineParams {
  int samples_per_interval = 4;  // constraint samples inside each path interval
  double nlopt_relative_tolerance = 1e-10;
  int nlopt_max_evaluations = 2000;
  int dense_samples = 400;             // limit check of the refit over [0, T]
  double saturation_tolerance = 1e-3;  // R in [1 - tol, 1] ends the refit loop
  int max_refits = 30;

  void Validate() const;
};

struct MinTimeBSplineResult {
  enum class Status { kOk, kNloptFailed, kNotConverged };
  Status status = Status::kOk;
  std::optional<BSpline> trajectory;  // s(t), t in [0, duration_s]
  std::vector<double> chi;            // 1 / lambda_i per path interval (NLopt solution)
  std::vector<double> chi_bound;      // the tightest limit's bound on each chi_i (analytic)
  std::vector<double> point_times_s;  // t_i of the path points after step 2
  double duration_s = 0.0;
  // Largest ratios over the dense samples: |v| / v_max, max_l |a_l| / a_max,l, max_l |j_l| /
  // j_max,l.
  double speed_ratio = 0.0, acceleration_ratio = 0.0, jerk_ratio = 0.0;
  int nlopt_result = 0;  // nlopt::result code
  int nlopt_evaluations = 0;
  int refits = 0;
  double cost = 0.0;  // objective (21) at the NLopt solution
  double solve_time_s = 0.0;

  bool ok() const { return status == Status::kOk; }
};
std::ostream& operator<<(std::ostream& out, const MinTimeBSplineResult& result);

// path_points: q_0..q_n, at least 6 (a quintic needs 6 control points), consecutive points apart;
// v0/a0 and vf/af the end states. Throws std::invalid_argument on bad limits, too few or repeated
// points, non-finite input, or an end speed above max_speed_mps.
MinTimeBSplineResult PlanMinTimeBSpline(const std::vector<Eigen::Vector3d>& path_points,
                                        const Eigen::Vector3d& v0, const Eigen::Vector3d& a0,
                                        const Eigen::Vector3d& vf, const Eigen::Vector3d& af,
                                        const DynamicLimits& limits,
                                        const MinTimeBSplineParams& params = {});

}  // namespace aperture::planning
