#include "planning/approach_planner.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>

#include "control/constants.h"
#include "control/require.h"
#include "planning/fast_acos.h"

namespace aperture::planning {
namespace {

using control::kPi;
constexpr double kNoBound = std::numeric_limits<double>::infinity();

double WrapAngle(double angle) { return std::remainder(angle, 2.0 * kPi); }

// Unit horizontal direction perpendicular-ish fallback for degenerate geometry.
Eigen::Vector3d AnyPerpendicular(const Eigen::Vector3d& z) {
  const Eigen::Vector3d axis =
      std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (axis - axis.dot(z) * z).normalized();
}

// Rotation W <- A of the start grid (parameters comment).
Eigen::Matrix3d ApproachFrame(const ApproachTarget& target) {
  Eigen::Vector3d back(-target.v_W.x(), -target.v_W.y(), 0.0);
  if (back.norm() < 1e-6) {
    const Eigen::Vector3d away = target.p_W - target.gap_center_W;
    back = Eigen::Vector3d(away.x(), away.y(), 0.0);
  }
  if (back.norm() < 1e-6) back = Eigen::Vector3d::UnitX();
  Eigen::Matrix3d R_WA;
  R_WA.col(0) = back.normalized();
  R_WA.col(2) = Eigen::Vector3d::UnitZ();
  R_WA.col(1) = R_WA.col(2).cross(R_WA.col(0));
  return R_WA;
}

}  // namespace

Eigen::Vector3d OptimalOpticalAxis(const Eigen::Vector3d& d_W, const Eigen::Vector3d& z_B_W,
                                   double k) {
  const Eigen::Vector3d d_perp = d_W - d_W.dot(z_B_W) * z_B_W;
  const double norm = d_perp.norm();
  const Eigen::Vector3d u = norm > 1e-12 * std::max(1.0, d_W.norm())
                                ? Eigen::Vector3d(d_perp / norm)
                                : AnyPerpendicular(z_B_W);
  return std::sqrt(std::max(0.0, 1.0 - k * k)) * u + k * z_B_W;  // (8)
}

double MinimumViewAngle(const Eigen::Vector3d& d_W, const Eigen::Vector3d& z_B_W, double k) {
  const double d_norm = d_W.norm();
  if (d_norm == 0.0) return 0.0;
  const double d_z = d_W.dot(z_B_W);
  const double d_perp = std::sqrt(std::max(0.0, d_norm * d_norm - d_z * d_z));
  const double cosine = (std::sqrt(std::max(0.0, 1.0 - k * k)) * d_perp + k * d_z) / d_norm;
  return std::acos(std::clamp(cosine, -1.0, 1.0));  // (9)
}

double PerceptionAwareHeading(const Eigen::Vector3d& d_W, const Eigen::Vector3d& z_B_W,
                              const Eigen::Vector3d& optical_axis_B) {
  const Eigen::Vector3d o = optical_axis_B.normalized();
  const double k = o.z();
  const Eigen::Vector3d r3 = OptimalOpticalAxis(d_W, z_B_W, k);
  // The part of r3* perpendicular to z_B must be cos(phi) x_B + sin(phi) y_B, phi the camera's
  // azimuth in B; with y_B = z_B x x_B this gives x_B = cos(phi) u - sin(phi) (z_B x u).
  const Eigen::Vector3d u = (r3 - k * z_B_W).normalized();
  const double phi = std::atan2(o.y(), o.x());
  const Eigen::Vector3d x_B = std::cos(phi) * u - std::sin(phi) * z_B_W.cross(u);
  // (F.11): x_B is perpendicular to y_C, so its horizontal projection is along x_C.
  return std::atan2(x_B.y(), x_B.x());
}

ApproachTarget ApproachTarget::FromTraverse(const TraverseTrajectory& traverse) {
  ApproachTarget target;
  target.p_W = traverse.start_position_W();
  target.v_W = traverse.start_velocity_W();
  target.a_W = traverse.plane_gravity_W();
  target.gap_center_W = traverse.gap().p_WG;
  return target;
}

void ApproachPlannerParameters::Validate() const {
  for (int i = 0; i < 3; ++i) {
    control::Require(std::isfinite(start_offset_min_A[i]) && std::isfinite(start_offset_max_A[i]) &&
                         start_offset_max_A[i] >= start_offset_min_A[i],
                     "ApproachPlannerParameters.start_offset_max_A[i] - start_offset_min_A[i]",
                     start_offset_max_A[i] - start_offset_min_A[i], "must be finite and >= 0");
    control::Require(start_counts[i] >= 1, "ApproachPlannerParameters.start_counts[i]",
                     start_counts[i], "must be >= 1");
  }
  control::RequirePositive(duration_min_s, "ApproachPlannerParameters.duration_min_s");
  control::Require(std::isfinite(duration_max_s) && duration_max_s >= duration_min_s,
                   "ApproachPlannerParameters.duration_max_s", duration_max_s,
                   "must be finite and >= duration_min_s");
  control::Require(duration_count >= 1, "ApproachPlannerParameters.duration_count", duration_count,
                   "must be >= 1");
  control::Require(samples_per_candidate >= 2, "ApproachPlannerParameters.samples_per_candidate",
                   samples_per_candidate, "must be >= 2 (both ends)");
  control::RequirePositive(view_angle_normalization_rad,
                           "ApproachPlannerParameters.view_angle_normalization_rad");
  control::RequirePositive(start_distance_normalization_m,
                           "ApproachPlannerParameters.start_distance_normalization_m");
  control::Require(
      !std::isnan(min_height_m) && min_height_m < std::numeric_limits<double>::infinity(),
      "ApproachPlannerParameters.min_height_m", min_height_m,
      "must be a height or -infinity (no floor)");
  control::RequirePositive(max_view_angle_rad, "ApproachPlannerParameters.max_view_angle_rad");
  control::RequireNonNegative(max_overshoot_m, "ApproachPlannerParameters.max_overshoot_m");
  const double axis_norm = optical_axis_B.norm();
  control::Require(optical_axis_B.allFinite() && axis_norm > 0.0 &&
                       std::abs(optical_axis_B.z()) < 0.999 * axis_norm,
                   "ApproachPlannerParameters.optical_axis_B.z / |optical_axis_B|",
                   axis_norm > 0.0 ? optical_axis_B.z() / axis_norm : 0.0,
                   "the optical axis must be non-zero and not parallel to z_B");
  limits.Validate();
}

std::ostream& operator<<(std::ostream& os, const ApproachPlan& plan) {
  os << "ApproachPlan{candidates=" << plan.candidates
     << ", feasibility_tests=" << plan.feasibility_tests
     << ", solve_time=" << plan.solve_time_s * 1e3 << " ms";
  if (plan.best) {
    os << ", best: T=" << plan.best->primitive.duration_s()
       << " s, start=" << plan.best->primitive.initial_position_W().transpose()
       << ", theta_rms=" << plan.best->view_angle_rms_rad
       << " rad, d0=" << plan.best->start_distance_m << " m, cost=" << plan.best->cost;
  } else {
    os << ", no valid candidate";
  }
  return os << "}";
}

ApproachPlanner::ApproachPlanner(const ApproachPlannerParameters& parameters)
    : parameters_(parameters) {
  parameters_.Validate();
  axis_to_z_B_rad_ = std::acos(parameters_.optical_axis_B.normalized().z());
}

Eigen::Vector3d ApproachPlanner::StartPosition(const ApproachTarget& target, int i, int j,
                                               int l) const {
  const Eigen::Vector3i& counts = parameters_.start_counts;
  const Eigen::Vector3d& lo = parameters_.start_offset_min_A;
  const Eigen::Vector3d& hi = parameters_.start_offset_max_A;
  const int index[3] = {i, j, l};
  Eigen::Vector3d offset_A;
  for (int axis = 0; axis < 3; ++axis) {
    offset_A[axis] = counts[axis] == 1
                         ? lo[axis]
                         : lo[axis] + (hi[axis] - lo[axis]) * index[axis] / (counts[axis] - 1);
  }
  return target.p_W + ApproachFrame(target) * offset_A;
}

double ApproachPlanner::Duration(int n) const {
  const int count = parameters_.duration_count;
  return count == 1
             ? parameters_.duration_min_s
             : parameters_.duration_min_s +
                   (parameters_.duration_max_s - parameters_.duration_min_s) * n / (count - 1);
}

bool ApproachPlanner::ScorePerception(const MotionPrimitive& primitive,
                                      const Eigen::Vector3d& gap_center_W, double cost_bound,
                                      ApproachCandidate& candidate) const {
  // Polynomial coefficients per axis, evaluated by Horner (the primitive's formulas, inlined).
  const Eigen::Vector3d& p0 = primitive.initial_position_W();
  const Eigen::Vector3d& v0 = primitive.initial_velocity_W();
  const Eigen::Vector3d c0 = primitive.initial_acceleration_W() +
                             Eigen::Vector3d(0.0, 0.0, parameters_.limits.gravity_mps2);
  const Eigen::Vector3d a2 = 0.5 * primitive.initial_acceleration_W();
  const Eigen::Vector3d& g = primitive.gamma();
  const Eigen::Vector3d b2 = 0.5 * primitive.beta();
  const Eigen::Vector3d a6 = primitive.alpha() / 6.0;
  const Eigen::Vector3d g6 = g / 6.0;
  const Eigen::Vector3d b24 = primitive.beta() / 24.0;
  const Eigen::Vector3d a120 = primitive.alpha() / 120.0;
  const int n = parameters_.samples_per_candidate;
  const double dt = primitive.duration_s() / (n - 1);
  candidate.start_distance_m = (gap_center_W - p0).norm();
  const double distance_cost =
      candidate.start_distance_m / parameters_.start_distance_normalization_m;
  // Branch and bound: theta_rms >= sqrt(partial sum / n), so once the partial sum of squares
  // exceeds this the cost (10) cannot get below cost_bound (infinite bound: never).
  const double angle_budget =
      std::max(0.0, cost_bound - distance_cost) * parameters_.view_angle_normalization_rad;
  const double max_sum_sq = std::isfinite(cost_bound) ? n * angle_budget * angle_budget
                                                      : std::numeric_limits<double>::infinity();
  if (!(distance_cost < cost_bound)) return false;
  double sum_sq = 0.0, max_angle = 0.0;
  for (int s = 0; s < n; ++s) {
    const double t = s * dt;
    const Eigen::Vector3d p = p0 + t * (v0 + t * (a2 + t * (g6 + t * (b24 + t * a120))));
    const Eigen::Vector3d c = c0 + t * (g + t * (b2 + t * a6));  // thrust vector a - g_W
    const Eigen::Vector3d d = gap_center_W - p;
    // (9) on the sphere: the optical axis keeps the angle beta = acos(k) to z_B = c / |c| and
    // the yaw turns it freely about z_B, so the nearest it gets to d is |phi - beta|, phi the
    // angle between d and z_B (expanding the cosine gives (9)). One square root, one division and
    // one FastAcos per sample.
    const double product = d.squaredNorm() * c.squaredNorm();
    const double angle =
        product > 0.0 ? std::abs(FastAcos(d.dot(c) / std::sqrt(product)) - axis_to_z_B_rad_) : 0.0;
    sum_sq += angle * angle;
    max_angle = std::max(max_angle, angle);
    if (sum_sq > max_sum_sq) return false;
  }
  candidate.view_angle_rms_rad = std::sqrt(sum_sq / n);
  candidate.gap_in_view = max_angle <= parameters_.max_view_angle_rad;
  candidate.cost =
      candidate.view_angle_rms_rad / parameters_.view_angle_normalization_rad + distance_cost;
  return candidate.cost < cost_bound;  // (10)
}

ApproachCandidate ApproachPlanner::EvaluateCandidate(const ApproachTarget& target,
                                                     const Eigen::Vector3d& start_W,
                                                     double duration_s) const {
  ApproachCandidate candidate;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  candidate.primitive =
      MotionPrimitive(start_W, zero, zero, target.p_W, target.v_W, target.a_W, duration_s);
  ScorePerception(candidate.primitive, target.gap_center_W, kNoBound, candidate);
  candidate.above_floor = AboveFloor(candidate.primitive);
  candidate.short_of_target = ShortOfTarget(candidate.primitive, target);
  candidate.feasibility = CheckInputFeasibility(candidate.primitive, parameters_.limits);
  return candidate;
}

bool ApproachPlanner::AboveFloor(const MotionPrimitive& primitive) const {
  return !std::isfinite(parameters_.min_height_m) ||
         MinimumProjection(primitive, Eigen::Vector3d::UnitZ()) >= parameters_.min_height_m;
}

bool ApproachPlanner::ShortOfTarget(const MotionPrimitive& primitive,
                                    const ApproachTarget& target) const {
  const Eigen::Vector3d to_gap_W = target.gap_center_W - target.p_W;
  if (to_gap_W.norm() == 0.0) return true;
  const Eigen::Vector3d u_W = to_gap_W.normalized();
  // max <u, p(t)> <= <u, p_0> + overshoot, as a minimum along -u.
  return MinimumProjection(primitive, -u_W) >= -u_W.dot(target.p_W) - parameters_.max_overshoot_m;
}

ApproachPlan ApproachPlanner::Plan(const ApproachTarget& target) const {
  if (!(target.p_W.allFinite() && target.v_W.allFinite() && target.a_W.allFinite() &&
        target.gap_center_W.allFinite())) {
    throw std::invalid_argument(
        "ApproachPlanner::Plan: the target has a non-finite component; build it from a "
        "successful traverse optimisation (ApproachTarget::FromTraverse)");
  }
  const auto start_time = std::chrono::steady_clock::now();
  const Eigen::Matrix3d R_WA = ApproachFrame(target);
  const Eigen::Vector3i& counts = parameters_.start_counts;
  const Eigen::Vector3d& lo = parameters_.start_offset_min_A;
  const Eigen::Vector3d& hi = parameters_.start_offset_max_A;
  Eigen::Vector3d step_A = Eigen::Vector3d::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    if (counts[axis] > 1) step_A[axis] = (hi[axis] - lo[axis]) / (counts[axis] - 1);
  }
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  ApproachPlan plan;
  ApproachCandidate candidate;
  double best_cost = std::numeric_limits<double>::infinity();
  for (int n = 0; n < parameters_.duration_count; ++n) {
    const double duration_s = Duration(n);
    for (int i = 0; i < counts[0]; ++i) {
      for (int j = 0; j < counts[1]; ++j) {
        for (int l = 0; l < counts[2]; ++l) {
          const Eigen::Vector3d offset_A = lo + Eigen::Vector3d(i, j, l).cwiseProduct(step_A);
          const Eigen::Vector3d start_W = target.p_W + R_WA * offset_A;
          ++plan.candidates;
          candidate.primitive =
              MotionPrimitive(start_W, zero, zero, target.p_W, target.v_W, target.a_W, duration_s);
          if (!ScorePerception(candidate.primitive, target.gap_center_W, best_cost, candidate) ||
              !candidate.gap_in_view) {
            continue;
          }
          candidate.above_floor = AboveFloor(candidate.primitive);
          candidate.short_of_target = ShortOfTarget(candidate.primitive, target);
          if (!candidate.above_floor || !candidate.short_of_target) continue;
          ++plan.feasibility_tests;
          candidate.feasibility = CheckInputFeasibility(candidate.primitive, parameters_.limits);
          if (candidate.feasibility != Feasibility::kFeasible) continue;
          best_cost = candidate.cost;
          plan.best = candidate;
        }
      }
    }
  }
  plan.solve_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return plan;
}

ApproachCandidate ApproachPlanner::Replan(const ApproachTarget& target, const Eigen::Vector3d& p_W,
                                          const Eigen::Vector3d& v_W, const Eigen::Vector3d& a_W,
                                          double remaining_s) const {
  if (!(std::isfinite(remaining_s) && remaining_s > 0.0)) {
    throw std::invalid_argument(
        "ApproachPlanner::Replan: remaining_s = " + std::to_string(remaining_s) +
        " must be positive; switch to the traverse when it reaches 0");
  }
  ApproachCandidate candidate;
  candidate.primitive =
      MotionPrimitive(p_W, v_W, a_W, target.p_W, target.v_W, target.a_W, remaining_s);
  candidate.feasibility = CheckInputFeasibility(candidate.primitive, parameters_.limits);
  ScorePerception(candidate.primitive, target.gap_center_W, kNoBound, candidate);
  candidate.above_floor = AboveFloor(candidate.primitive);
  candidate.short_of_target = ShortOfTarget(candidate.primitive, target);
  return candidate;
}

double ApproachPlanner::HeadingAt(const MotionPrimitive& primitive,
                                  const Eigen::Vector3d& gap_center_W, double t_s) const {
  const Eigen::Vector3d c =
      primitive.Acceleration(t_s) + Eigen::Vector3d(0.0, 0.0, parameters_.limits.gravity_mps2);
  return PerceptionAwareHeading(gap_center_W - primitive.Position(t_s), c.normalized(),
                                parameters_.optical_axis_B);
}

control::TrajectoryPoint ApproachPlanner::Sample(const MotionPrimitive& primitive,
                                                 const Eigen::Vector3d& gap_center_W,
                                                 double t_s) const {
  control::TrajectoryPoint point = primitive.Sample(t_s);
  const double h = 1e-3;
  const double psi = HeadingAt(primitive, gap_center_W, t_s);
  const double before = WrapAngle(psi - HeadingAt(primitive, gap_center_W, t_s - h));
  const double after = WrapAngle(HeadingAt(primitive, gap_center_W, t_s + h) - psi);
  point.heading_rad = psi;
  point.heading_rate_radps = (before + after) / (2.0 * h);
  point.heading_acc_radps2 = (after - before) / (h * h);
  return point;
}

}  // namespace aperture::planning
