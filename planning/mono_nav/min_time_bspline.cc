#include "planning/mono_nav/min_time_bspline.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlopt.hpp>
#include <stdexcept>

namespace aperture::planning {
namespace {

constexpr int kDegree = 5;  // quintic: jerk-continuous (Sec. III-E)

// |s'|, |s''_l|, |s'''_l| at one constraint sample of interval `interval`.
struct Sample {
  int interval = 0;
  double speed = 0.0;                                      // |s'(u)|
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  // |s''_l(u)|
  Eigen::Vector3d jerk = Eigen::Vector3d::Zero();          // |s'''_l(u)|
};

struct Problem {
  std::vector<Sample> samples;
  const DynamicLimits* limits = nullptr;
  int evaluations = 0;
};

// Objective (21): sum over samples of (|s'(u)| chi_i - v_max)^2.
double SpeedExcessObjective(const std::vector<double>& chi, std::vector<double>& grad, void* data) {
  auto* problem = static_cast<Problem*>(data);
  ++problem->evaluations;
  if (!grad.empty()) std::fill(grad.begin(), grad.end(), 0.0);
  double cost = 0.0;
  for (const Sample& s : problem->samples) {
    const double residual = s.speed * chi[s.interval] - problem->limits->max_speed_mps;
    cost += residual * residual;
    if (!grad.empty()) grad[s.interval] += 2.0 * residual * s.speed;
  }
  return cost;
}

// Constraints (26)-(30) as c(chi) <= 0, 7 per sample (speed, 3 accelerations, 3 jerks). With
// chi_i > 0, |s''_l| chi^2 <= a_l  <=>  chi sqrt(|s''_l| / a_l) <= 1 and likewise with the cube
// root for jerk, so every constraint is affine in chi (the paper's A_in chi <= b_in) and the
// problem is a convex QP. Layout: result[7 k + m] = coefficient[m] * chi_interval(k) - 1.
void Constraints(unsigned m, double* result, unsigned n, const double* chi, double* grad,
                 void* data) {
  auto* problem = static_cast<Problem*>(data);
  const DynamicLimits& limits = *problem->limits;
  if (grad) std::fill(grad, grad + std::size_t(m) * n, 0.0);
  for (std::size_t k = 0; k < problem->samples.size(); ++k) {
    const Sample& s = problem->samples[k];
    double coefficient[7];
    coefficient[0] = s.speed / limits.max_speed_mps;
    for (int l = 0; l < 3; ++l) {
      coefficient[1 + l] = std::sqrt(s.acceleration[l] / limits.max_acceleration_mps2[l]);
      coefficient[4 + l] = std::cbrt(s.jerk[l] / limits.max_jerk_mps3[l]);
    }
    for (int c = 0; c < 7; ++c) {
      result[7 * k + c] = coefficient[c] * chi[s.interval] - 1.0;
      if (grad) grad[(7 * k + c) * n + s.interval] = coefficient[c];
    }
  }
}

// Upper bound on chi_i from one sample: the tightest of the speed, acceleration and jerk limits.
double ChiBound(const Sample& s, const DynamicLimits& limits) {
  double bound = s.speed > 0.0 ? limits.max_speed_mps / s.speed : INFINITY;
  for (int l = 0; l < 3; ++l) {
    if (s.acceleration[l] > 0.0) {
      bound = std::min(bound, std::sqrt(limits.max_acceleration_mps2[l] / s.acceleration[l]));
    }
    if (s.jerk[l] > 0.0) bound = std::min(bound, std::cbrt(limits.max_jerk_mps3[l] / s.jerk[l]));
  }
  return bound;
}

// Step 1: quintic B-spline interpolating the points at chord-length parameters in [0, 1].
BSpline InterpolatePath(const std::vector<Eigen::Vector3d>& points, std::vector<double>* params) {
  const int m = static_cast<int>(points.size());
  params->assign(m, 0.0);
  for (int i = 1; i < m; ++i) (*params)[i] = (*params)[i - 1] + (points[i] - points[i - 1]).norm();
  const double length = params->back();
  for (double& u : *params) u /= length;
  params->back() = 1.0;
  const std::vector<double> knots = BSpline::AveragedKnots(*params, kDegree, m);
  BSpline::ControlPoints zeros = BSpline::ControlPoints::Zero(m, 3);
  const BSpline basis(kDegree, knots, zeros);
  Eigen::MatrixXd N(m, m);
  BSpline::ControlPoints Q(m, 3);
  for (int i = 0; i < m; ++i) {
    N.row(i) = basis.BasisRow((*params)[i], 0);
    Q.row(i) = points[i].transpose();
  }
  return BSpline(kDegree, knots, N.fullPivLu().solve(Q));
}

// Step 3: least-squares quintic fit of (times, positions) with end position, velocity and
// acceleration as equality constraints (KKT system of (33)).
BSpline RefitInTime(const std::vector<double>& times, const std::vector<Eigen::Vector3d>& positions,
                    int control_points, const Eigen::Vector3d& v0, const Eigen::Vector3d& a0,
                    const Eigen::Vector3d& vf, const Eigen::Vector3d& af) {
  const std::vector<double> knots = BSpline::AveragedKnots(times, kDegree, control_points);
  const BSpline basis(kDegree, knots, BSpline::ControlPoints::Zero(control_points, 3));
  const int m = static_cast<int>(times.size());
  Eigen::MatrixXd A(m, control_points);
  Eigen::MatrixXd Y(m, 3);
  for (int i = 0; i < m; ++i) {
    A.row(i) = basis.BasisRow(times[i], 0);
    Y.row(i) = positions[i].transpose();
  }
  Eigen::MatrixXd C(6, control_points);
  Eigen::MatrixXd d(6, 3);
  const double t0 = times.front(), tf = times.back();
  C.row(0) = basis.BasisRow(t0, 0), d.row(0) = positions.front().transpose();
  C.row(1) = basis.BasisRow(t0, 1), d.row(1) = v0.transpose();
  C.row(2) = basis.BasisRow(t0, 2), d.row(2) = a0.transpose();
  C.row(3) = basis.BasisRow(tf, 0), d.row(3) = positions.back().transpose();
  C.row(4) = basis.BasisRow(tf, 1), d.row(4) = vf.transpose();
  C.row(5) = basis.BasisRow(tf, 2), d.row(5) = af.transpose();
  const int n = control_points;
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + 6, n + 6);
  kkt.topLeftCorner(n, n) = 2.0 * A.transpose() * A;
  kkt.topRightCorner(n, 6) = C.transpose();
  kkt.bottomLeftCorner(6, n) = C;
  Eigen::MatrixXd rhs(n + 6, 3);
  rhs.topRows(n) = 2.0 * A.transpose() * Y;
  rhs.bottomRows(6) = d;
  const Eigen::MatrixXd solution = kkt.colPivHouseholderQr().solve(rhs);
  return BSpline(kDegree, knots, solution.topRows(n));
}

// Largest ratios of |v|, |a_l|, |j_l| to their limits over `count` uniform samples.
void Ratios(const BSpline& s, const DynamicLimits& limits, int count, MinTimeBSplineResult* r) {
  r->speed_ratio = r->acceleration_ratio = r->jerk_ratio = 0.0;
  for (int k = 0; k <= count; ++k) {
    const double t =
        s.StartParameter() + (s.EndParameter() - s.StartParameter()) * double(k) / count;
    r->speed_ratio = std::max(r->speed_ratio, s.Evaluate(t, 1).norm() / limits.max_speed_mps);
    r->acceleration_ratio = std::max(
        r->acceleration_ratio,
        s.Evaluate(t, 2).cwiseAbs().cwiseQuotient(limits.max_acceleration_mps2).maxCoeff());
    r->jerk_ratio = std::max(
        r->jerk_ratio, s.Evaluate(t, 3).cwiseAbs().cwiseQuotient(limits.max_jerk_mps3).maxCoeff());
  }
}

}  // namespace

double DynamicLimits::JerkBound(double min_thrust_mps2, double max_body_rate_radps) {
  if (!(min_thrust_mps2 > 0.0) || !(max_body_rate_radps > 0.0)) {
    throw std::invalid_argument("jerk bound: f_min and omega_max must be > 0");
  }
  return min_thrust_mps2 * max_body_rate_radps / std::sqrt(3.0);
}

void DynamicLimits::Validate() const {
  if (!(max_speed_mps > 0.0) || !std::isfinite(max_speed_mps)) {
    throw std::invalid_argument("dynamic limits: max_speed_mps must be > 0");
  }
  if (!(max_acceleration_mps2.array() > 0.0).all() || !max_acceleration_mps2.allFinite()) {
    throw std::invalid_argument("dynamic limits: every max_acceleration_mps2 must be > 0");
  }
  if (!(max_jerk_mps3.array() > 0.0).all() || !max_jerk_mps3.allFinite()) {
    throw std::invalid_argument("dynamic limits: every max_jerk_mps3 must be > 0");
  }
}

void MinTimeBSplineParams::Validate() const {
  if (samples_per_interval < 1 || dense_samples < 10 || !(saturation_tolerance > 0.0) ||
      max_refits < 1 || nlopt_max_evaluations < 1 || !(nlopt_relative_tolerance > 0.0)) {
    throw std::invalid_argument(
        "min-time B-spline: need samples_per_interval >= 1, "
        "dense_samples >= 10, saturation_tolerance > 0, max_refits >= 1 "
        "and positive NLopt settings");
  }
}

std::ostream& operator<<(std::ostream& out, const MinTimeBSplineResult& result) {
  const char* status = result.status == MinTimeBSplineResult::Status::kOk ? "ok"
                       : result.status == MinTimeBSplineResult::Status::kNloptFailed
                           ? "nlopt failed"
                           : "refit not converged";
  return out << "MinTimeBSpline{" << status << ", T " << result.duration_s << " s, v/a/j ratios "
             << result.speed_ratio << '/' << result.acceleration_ratio << '/' << result.jerk_ratio
             << ", nlopt " << result.nlopt_result << " in " << result.nlopt_evaluations
             << " evaluations, " << result.refits << " refits, " << result.solve_time_s * 1e3
             << " ms}";
}

MinTimeBSplineResult PlanMinTimeBSpline(const std::vector<Eigen::Vector3d>& path_points,
                                        const Eigen::Vector3d& v0, const Eigen::Vector3d& a0,
                                        const Eigen::Vector3d& vf, const Eigen::Vector3d& af,
                                        const DynamicLimits& limits,
                                        const MinTimeBSplineParams& params) {
  limits.Validate();
  params.Validate();
  if (path_points.size() < kDegree + 1) {
    throw std::invalid_argument("min-time B-spline: need at least 6 path points, got " +
                                std::to_string(path_points.size()));
  }
  for (std::size_t i = 0; i < path_points.size(); ++i) {
    if (!path_points[i].allFinite())
      throw std::invalid_argument("min-time B-spline: non-finite point");
    if (i > 0 && !((path_points[i] - path_points[i - 1]).norm() > 1e-9)) {
      throw std::invalid_argument("min-time B-spline: path points " + std::to_string(i - 1) +
                                  " and " + std::to_string(i) + " coincide");
    }
  }
  if (!v0.allFinite() || !a0.allFinite() || !vf.allFinite() || !af.allFinite() ||
      v0.norm() > limits.max_speed_mps || vf.norm() > limits.max_speed_mps) {
    throw std::invalid_argument(
        "min-time B-spline: end states must be finite with speeds within "
        "max_speed_mps");
  }
  const auto start = std::chrono::steady_clock::now();
  MinTimeBSplineResult result;

  // 1. Geometric spline s(u).
  std::vector<double> u;
  const BSpline path = InterpolatePath(path_points, &u);
  const int intervals = static_cast<int>(path_points.size()) - 1;

  // 2. Time scaling: constraint samples, analytic per-interval bounds, NLopt.
  Problem problem;
  problem.limits = &limits;
  result.chi_bound.assign(intervals, INFINITY);
  for (int i = 0; i < intervals; ++i) {
    for (int k = 0; k <= params.samples_per_interval; ++k) {
      const double uk = u[i] + (u[i + 1] - u[i]) * double(k) / params.samples_per_interval;
      Sample s;
      s.interval = i;
      s.speed = path.Evaluate(uk, 1).norm();
      s.acceleration = path.Evaluate(uk, 2).cwiseAbs();
      s.jerk = path.Evaluate(uk, 3).cwiseAbs();
      result.chi_bound[i] = std::min(result.chi_bound[i], ChiBound(s, limits));
      problem.samples.push_back(s);
    }
  }
  nlopt::opt optimizer(nlopt::LD_SLSQP, intervals);
  optimizer.set_lower_bounds(std::vector<double>(intervals, 1e-9));
  optimizer.set_min_objective(SpeedExcessObjective, &problem);
  optimizer.add_inequality_mconstraint(Constraints, &problem,
                                       std::vector<double>(7 * problem.samples.size(), 1e-12));
  optimizer.set_xtol_rel(params.nlopt_relative_tolerance);
  optimizer.set_maxeval(params.nlopt_max_evaluations);
  std::vector<double> chi(intervals);
  for (int i = 0; i < intervals; ++i) chi[i] = 0.1 * result.chi_bound[i];  // feasible start
  try {
    const nlopt::result code = optimizer.optimize(chi, result.cost);
    result.nlopt_result = static_cast<int>(code);
  } catch (const nlopt::roundoff_limited&) {
    result.nlopt_result = static_cast<int>(nlopt::ROUNDOFF_LIMITED);
  } catch (const std::exception&) {
    result.status = MinTimeBSplineResult::Status::kNloptFailed;
  }
  result.nlopt_evaluations = problem.evaluations;
  result.chi = chi;
  for (double x : chi) {
    if (!(x > 0.0) || !std::isfinite(x)) result.status = MinTimeBSplineResult::Status::kNloptFailed;
  }
  if (!result.ok()) {
    result.solve_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }
  result.point_times_s.assign(intervals + 1, 0.0);
  for (int i = 0; i < intervals; ++i) {
    result.point_times_s[i + 1] = result.point_times_s[i] + (u[i + 1] - u[i]) / chi[i];
  }

  // 3.-4. Refit in time on the time-scaled samples; stretch until the binding limit saturates.
  std::vector<double> times;
  std::vector<Eigen::Vector3d> positions;
  for (int i = 0; i < intervals; ++i) {
    for (int k = (i == 0 ? 0 : 1); k <= params.samples_per_interval; ++k) {
      const double fraction = double(k) / params.samples_per_interval;
      times.push_back(result.point_times_s[i] +
                      fraction * (result.point_times_s[i + 1] - result.point_times_s[i]));
      positions.push_back(path.Evaluate(u[i] + fraction * (u[i + 1] - u[i]), 0));
    }
  }
  const int control_points = std::min<int>(int(times.size()), intervals + 1 + 4);
  double stretch = 1.0;
  result.status = MinTimeBSplineResult::Status::kNotConverged;
  for (result.refits = 1; result.refits <= params.max_refits; ++result.refits) {
    std::vector<double> scaled = times;
    for (double& t : scaled) t *= stretch;
    BSpline refit = RefitInTime(scaled, positions, control_points, v0, a0, vf, af);
    Ratios(refit, limits, params.dense_samples, &result);
    const double ratio = std::max(
        {result.speed_ratio, std::sqrt(result.acceleration_ratio), std::cbrt(result.jerk_ratio)});
    result.trajectory = refit;
    result.duration_s = refit.EndParameter() - refit.StartParameter();
    if (ratio <= 1.0 + 1e-12 && ratio >= 1.0 - params.saturation_tolerance) {
      result.status = MinTimeBSplineResult::Status::kOk;
      break;
    }
    stretch *= ratio;
  }
  if (result.refits > params.max_refits) result.refits = params.max_refits;
  result.solve_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace aperture::planning
