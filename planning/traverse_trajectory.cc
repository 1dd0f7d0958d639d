#include "planning/traverse_trajectory.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlopt.hpp>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/require.h"

namespace aperture::planning {
namespace {

void ValidateGap(const GapPose& gap) {
  const double orthogonality_error =
      (gap.R_WG.transpose() * gap.R_WG - Eigen::Matrix3d::Identity()).norm();
  control::Require(
      gap.p_WG.allFinite() && orthogonality_error < 1e-6 && gap.R_WG.determinant() > 0.0,
      "GapPose: R_WG orthogonality error", orthogonality_error,
      "(R_WG must be a rotation matrix, p_WG finite; see traverse_trajectory.h for the axes)");
}

// The plane basis of the header comment.
struct PlaneBasis {
  Eigen::Vector3d e1, e2, e3;
  double g1, g2;
};

PlaneBasis ComputePlaneBasis(const Eigen::Matrix3d& R_WG, double gravity) {
  const Eigen::Vector3d g_W(0.0, 0.0, -gravity);
  PlaneBasis basis;
  basis.e2 = R_WG.col(2);
  basis.e3 = R_WG.col(1);
  basis.e1 = basis.e2.cross(basis.e3);
  if (g_W.dot(basis.e1) > 0.0) {
    basis.e3 = -basis.e3;
    basis.e1 = -basis.e1;
  }
  basis.g1 = g_W.dot(basis.e1);  // (1) projected on e1, <= 0
  basis.g2 = g_W.dot(basis.e2);
  return basis;
}

// Start velocity components of (3b) with l from (4).
double StartVelocity1(double g1, double t_c) { return -g1 * t_c; }
double StartVelocity2(double g2, double d, double t_c) { return d / t_c - 0.5 * g2 * t_c; }

struct ProblemData {
  double g1, g2, v_max;
  int evaluations = 0;
};

// Layout of x: [d (m), t_c (s)].
double TraverseTimeObjective(const std::vector<double>& x, std::vector<double>& grad, void* data) {
  ++static_cast<ProblemData*>(data)->evaluations;
  if (!grad.empty()) {
    grad[0] = 0.0;
    grad[1] = 1.0;
  }
  return x[1];
}

// (|v_0|^2 - v_max^2) / v_max^2 <= 0.
double SpeedConstraint(const std::vector<double>& x, std::vector<double>& grad, void* data) {
  const auto& p = *static_cast<const ProblemData*>(data);
  const double d = x[0], t = x[1];
  const double v1 = StartVelocity1(p.g1, t), v2 = StartVelocity2(p.g2, d, t);
  const double scale = 1.0 / (p.v_max * p.v_max);
  if (!grad.empty()) {
    grad[0] = scale * 2.0 * v2 / t;
    grad[1] = scale * (2.0 * v1 * (-p.g1) + 2.0 * v2 * (-d / (t * t) - 0.5 * p.g2));
  }
  return scale * (v1 * v1 + v2 * v2) - 1.0;
}

// g_Pi,2 < 0 only: (sqrt(2 |g2| d) - v_2(t_c)) / v_max <= 0 (header comment).
double ClearanceConstraint(const std::vector<double>& x, std::vector<double>& grad, void* data) {
  const auto& p = *static_cast<const ProblemData*>(data);
  const double d = x[0], t = x[1];
  const double k = std::sqrt(2.0 * std::abs(p.g2));
  const double v2_at_gap = d / t + 0.5 * p.g2 * t;
  if (!grad.empty()) {
    grad[0] = (0.5 * k / std::sqrt(d) - 1.0 / t) / p.v_max;
    grad[1] = (d / (t * t) - 0.5 * p.g2) / p.v_max;
  }
  return (k * std::sqrt(d) - v2_at_gap) / p.v_max;
}

}  // namespace

void TraverseParameters::Validate() const {
  const std::string prefix = "TraverseParameters: ";
  control::RequirePositive(max_start_speed_mps, prefix + "max_start_speed_mps");
  control::RequirePositive(min_start_distance_m, prefix + "min_start_distance_m");
  control::Require(
      std::isfinite(max_start_distance_m) && max_start_distance_m > min_start_distance_m,
      prefix + "max_start_distance_m", max_start_distance_m,
      "must be finite and > min_start_distance_m");
  control::RequirePositive(max_time_to_gap_s, prefix + "max_time_to_gap_s");
  control::RequirePositive(gravity_mps2, prefix + "gravity_mps2");
  control::RequirePositive(relative_tolerance, prefix + "relative_tolerance");
  control::Require(max_evaluations > 0, prefix + "max_evaluations", max_evaluations, "must be > 0");
}

TraverseTrajectory::TraverseTrajectory(const GapPose& gap, double d_m, double time_to_gap_s,
                                       double gravity_mps2)
    : gap_(gap), d_m_(d_m), time_to_gap_s_(time_to_gap_s) {
  control::RequirePositive(d_m, "TraverseTrajectory: d_m");
  control::RequirePositive(time_to_gap_s, "TraverseTrajectory: time_to_gap_s");
  control::RequirePositive(gravity_mps2, "TraverseTrajectory: gravity_mps2");
  ValidateGap(gap);
  const PlaneBasis basis = ComputePlaneBasis(gap.R_WG, gravity_mps2);
  e1_W_ = basis.e1;
  e2_W_ = basis.e2;
  e3_W_ = basis.e3;
  g1_ = basis.g1;
  g2_ = basis.g2;
  const Eigen::Vector3d g_W(0.0, 0.0, -gravity_mps2);
  plane_gravity_W_ = g_W - g_W.dot(e3_W_) * e3_W_;  // (1)
  const double t_c = time_to_gap_s;
  l_m_ = 0.5 * std::abs(g1_) * t_c * t_c;          // (4) solved for l (g1 <= 0)
  p0_W_ = gap.p_WG - l_m_ * e1_W_ - d_m_ * e2_W_;  // (3a)
  v0_W_ = StartVelocity1(g1_, t_c) * e1_W_ + StartVelocity2(g2_, d_m_, t_c) * e2_W_;  // (3b)
  // End when p_2 = 2 d: g2 t^2 / 2 + v_2 t - 2 d = 0, smallest positive root in the form that
  // is stable for every sign of g2 (and g2 = 0). Without a real root (g2 < 0 and the clearance
  // constraint violated) the traverse ends at the e2 apex.
  const double v2 = v0_W_.dot(e2_W_);
  const double discriminant = v2 * v2 + 4.0 * g2_ * d_m_;
  if (discriminant >= 0.0 && v2 + std::sqrt(discriminant) > 0.0) {
    duration_s_ = 4.0 * d_m_ / (v2 + std::sqrt(discriminant));
  } else {
    duration_s_ = g2_ < 0.0 ? std::max(v2 / -g2_, t_c) : t_c;
  }
  const Eigen::Vector3d thrust_W = plane_gravity_W_ - g_W;  // = -<g, e3> e3
  thrust_mps2_ = thrust_W.norm();
  thrust_direction_W_ = thrust_mps2_ > 0.0 ? Eigen::Vector3d(thrust_W / thrust_mps2_) : e3_W_;
  // x_B from the start towards the gap centre (l e1 + d e2, which lies in Pi and so is normal to
  // the thrust): the perception-aware heading (8) of a forward camera at t = 0, so an approach
  // planned with it ends on the heading the traverse holds with zero body rates. (F.11): x_B's
  // horizontal projection is along x_C. Fallback e2, then e1, if that projection vanishes.
  Eigen::Vector3d forward = gap.p_WG - p0_W_;
  if (Eigen::Vector2d(forward.x(), forward.y()).norm() < 1e-9 * forward.norm()) forward = e2_W_;
  if (Eigen::Vector2d(forward.x(), forward.y()).norm() < 1e-6) forward = e1_W_;
  heading_rad_ = std::atan2(forward.y(), forward.x());
}

Eigen::Vector3d TraverseTrajectory::Position(double t) const {
  return p0_W_ + v0_W_ * t + 0.5 * plane_gravity_W_ * t * t;
}

Eigen::Vector3d TraverseTrajectory::Velocity(double t) const {
  return v0_W_ + plane_gravity_W_ * t;
}

control::TrajectoryPoint TraverseTrajectory::Sample(double t_s) const {
  control::TrajectoryPoint point;
  point.t_s = t_s;
  point.p_W = Position(t_s);
  point.v_W = Velocity(t_s);
  point.a_W = plane_gravity_W_;
  point.heading_rad = heading_rad_;
  return point;
}

std::ostream& operator<<(std::ostream& os, const TraverseOptimizationResult& result) {
  const char* status = result.status == TraverseOptimizationResult::Status::kSuccess ? "success"
                       : result.status == TraverseOptimizationResult::Status::kInfeasible
                           ? "infeasible"
                           : "solver failure";
  os << "TraverseOptimization{status=" << status << ", iterations=" << result.iterations
     << ", cost(t_c)=" << result.cost << " s, solve_time=" << result.solve_time_s * 1e3
     << " ms, max_violation=" << result.max_constraint_violation;
  if (result.trajectory) {
    os << ", d=" << result.trajectory->d_m() << " m, l=" << result.trajectory->l_m()
       << " m, |v0|=" << result.trajectory->start_velocity_W().norm() << " m/s";
  }
  return os << "}";
}

TraverseOptimizationResult OptimizeTraverseTrajectory(const GapPose& gap,
                                                      const TraverseParameters& parameters) {
  parameters.Validate();
  ValidateGap(gap);
  const auto start = std::chrono::steady_clock::now();
  const PlaneBasis basis = ComputePlaneBasis(gap.R_WG, parameters.gravity_mps2);
  ProblemData data{basis.g1, basis.g2, parameters.max_start_speed_mps};
  const double t_min = 1e-3;  // keeps d / t_c finite; far below any feasible t_c

  nlopt::opt optimizer(nlopt::LD_SLSQP, 2);
  optimizer.set_lower_bounds({parameters.min_start_distance_m, t_min});
  optimizer.set_upper_bounds({parameters.max_start_distance_m, parameters.max_time_to_gap_s});
  optimizer.set_min_objective(TraverseTimeObjective, &data);
  optimizer.add_inequality_constraint(SpeedConstraint, &data, 1e-12);
  const bool needs_clearance = basis.g2 < 0.0;
  if (needs_clearance) optimizer.add_inequality_constraint(ClearanceConstraint, &data, 1e-12);
  optimizer.set_xtol_rel(parameters.relative_tolerance);
  optimizer.set_maxeval(parameters.max_evaluations);

  // Start from the shortest t_c on a coarse grid that is feasible with d = d_min, or mid-range.
  std::vector<double> x = {parameters.min_start_distance_m, 0.5 * parameters.max_time_to_gap_s};
  std::vector<double> no_grad;
  for (int k = 1; k <= 64; ++k) {
    const std::vector<double> trial = {parameters.min_start_distance_m,
                                       parameters.max_time_to_gap_s * k / 64.0};
    if (SpeedConstraint(trial, no_grad, &data) <= 0.0 &&
        (!needs_clearance || ClearanceConstraint(trial, no_grad, &data) <= 0.0)) {
      x = trial;
      break;
    }
  }

  TraverseOptimizationResult result;
  double cost = 0.0;
  try {
    optimizer.optimize(x, cost);
  } catch (const nlopt::roundoff_limited&) {
    // SLSQP at its precision limit: x holds the best point; the constraint check below decides.
  } catch (const std::exception&) {
    result.status = TraverseOptimizationResult::Status::kSolverFailure;
    result.iterations = data.evaluations;
    result.solve_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }
  result.iterations = data.evaluations;
  result.cost = x[1];
  result.max_constraint_violation = std::max(0.0, SpeedConstraint(x, no_grad, &data));
  if (needs_clearance) {
    result.max_constraint_violation =
        std::max(result.max_constraint_violation, ClearanceConstraint(x, no_grad, &data));
  }
  // 1e-9 on constraints scaled to O(1): |v0| within ~1.5e-9 m/s of v_max.
  result.status = result.max_constraint_violation <= 1e-9
                      ? TraverseOptimizationResult::Status::kSuccess
                      : TraverseOptimizationResult::Status::kInfeasible;
  result.trajectory.emplace(gap, x[0], x[1], parameters.gravity_mps2);
  result.solve_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace aperture::planning
