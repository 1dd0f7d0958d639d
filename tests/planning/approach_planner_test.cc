#include "planning/approach_planner.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include "control/constants.h"

namespace aperture::planning {
namespace {

using control::kPi;

// Body attitude from thrust direction and heading, Faessler thesis (F.9)-(F.11).
Eigen::Matrix3d AttitudeFromHeading(const Eigen::Vector3d& z_B, double psi) {
  const Eigen::Vector3d y_C(-std::sin(psi), std::cos(psi), 0.0);
  const Eigen::Vector3d x_B = y_C.cross(z_B).normalized();
  Eigen::Matrix3d R_WB;
  R_WB << x_B, z_B.cross(x_B), z_B;
  return R_WB;
}

double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// (8)/(9) against a brute-force sweep of the heading: for random gap directions, thrust tilts up
// to 60 deg and three camera mounts, the best sampled heading (step 2e-5 rad) reaches the closed-
// form minimum angle to 1e-8 rad (the angle is quadratic in the heading error near the optimum,
// so the sweep's error is ~ step^2) and lies within 1e-4 rad of the closed-form heading (the
// minimiser is resolved to a step; headings compared modulo 2 pi). The sweep is coarse (1e-3 rad)
// over the circle, then fine (2e-5 rad) around the coarse minimum.
TEST(PerceptionAwareYaw, MatchesBruteForceOverHeading) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d axes[3] = {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 0, 0.35),
                                   Eigen::Vector3d(0.6, 0.5, -0.2)};
  int cases = 0;
  while (cases < 30) {
    const Eigen::Vector3d d(3.0 * u(rng), 3.0 * u(rng), u(rng));
    const Eigen::Vector3d z_B =
        (Eigen::Vector3d::UnitZ() + 0.8 * Eigen::Vector3d(u(rng), u(rng), 0.0)).normalized();
    if (AngleBetween(z_B, Eigen::Vector3d::UnitZ()) > kPi / 3) continue;
    if ((d - d.dot(z_B) * z_B).norm() < 0.3 * d.norm()) continue;  // well-defined optimum
    const Eigen::Vector3d& axis_B = axes[cases % 3];
    const Eigen::Vector3d o = axis_B.normalized();
    ++cases;
    double best_angle = 1e9, best_psi = 0.0;
    const auto sweep = [&](double from, double to, double step) {
      for (double psi = from; psi < to; psi += step) {
        const double angle = AngleBetween(AttitudeFromHeading(z_B, psi) * o, d);
        if (angle < best_angle) {
          best_angle = angle;
          best_psi = psi;
        }
      }
    };
    sweep(-kPi, kPi, 1e-3);
    sweep(best_psi - 2e-3, best_psi + 2e-3, 2e-5);
    const double theta = MinimumViewAngle(d, z_B, o.z());
    EXPECT_NEAR(theta, best_angle, 1e-8) << "case " << cases;
    const double psi = PerceptionAwareHeading(d, z_B, axis_B);
    EXPECT_NEAR(std::remainder(psi - best_psi, 2.0 * kPi), 0.0, 1e-4) << "case " << cases;
    // The closed-form heading attains (9) exactly (up to rounding), and r3* satisfies (7).
    EXPECT_NEAR(AngleBetween(AttitudeFromHeading(z_B, psi) * o, d), theta, 1e-9);
    const Eigen::Vector3d r3 = OptimalOpticalAxis(d, z_B, o.z());
    EXPECT_NEAR(r3.norm(), 1.0, 1e-12);
    EXPECT_NEAR(r3.dot(z_B), o.z(), 1e-12);
    EXPECT_NEAR(AngleBetween(r3, d), theta, 1e-9);
  }
}

TEST(PerceptionAwareYaw, AlignedCaseHasZeroAngle) {
  // <d, z_B> = k |d| lets the axis point straight at the gap (the paper's special case).
  const Eigen::Vector3d z_B = Eigen::Vector3d::UnitZ();
  const double k = std::sin(0.2);
  const Eigen::Vector3d d = 2.0 * Eigen::Vector3d(std::cos(0.2), 0.0, std::sin(0.2));
  EXPECT_NEAR(MinimumViewAngle(d, z_B, k), 0.0, 1e-7);  // acos near 1: sqrt(eps) resolution
  EXPECT_LT((OptimalOpticalAxis(d, z_B, k) - d.normalized()).norm(), 1e-12);
}

GapPose TestGap() {
  GapPose gap;
  gap.p_WG = Eigen::Vector3d(5.0, 0.5, 1.8);
  Eigen::Matrix3d R0;
  R0 << Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX();
  gap.R_WG =
      Eigen::AngleAxisd(30.0 * kPi / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix() * R0;
  return gap;
}

ApproachTarget TestTarget() {
  const TraverseOptimizationResult result = OptimizeTraverseTrajectory(TestGap(), {});
  return ApproachTarget::FromTraverse(*result.trajectory);
}

ApproachPlannerParameters SmallGrid() {
  ApproachPlannerParameters parameters;
  parameters.start_counts = Eigen::Vector3i(4, 3, 3);
  parameters.duration_min_s = 0.6;
  parameters.duration_max_s = 3.0;
  parameters.duration_count = 6;
  parameters.limits.max_thrust_mps2 = 20.0;
  parameters.limits.max_body_rate_radps = 6.0;
  // Weighs the view angle so that the perception-best candidate is one the feasibility test
  // cannot certify (checked in PicksTheMinimumCostValidCandidate).
  parameters.view_angle_normalization_rad = 0.1;
  return parameters;
}

// The planner's choice equals the exhaustive minimum over every valid candidate, and the set is
// mixed enough that feasibility decides (a cheaper but invalid candidate exists).
TEST(ApproachPlanner, PicksTheMinimumCostValidCandidate) {
  const ApproachTarget target = TestTarget();
  ApproachPlannerParameters parameters = SmallGrid();
  parameters.min_height_m = 1.0;  // cuts the lowest starts (~0.8 m) and some dipping candidates
  const ApproachPlanner planner(parameters);
  const ApproachPlannerParameters& p = planner.parameters();
  double best_cost = 1e300, cheapest_any = 1e300;
  Eigen::Vector3d best_start = Eigen::Vector3d::Zero();
  double best_duration = 0.0;
  int valid = 0, total = 0, below_floor = 0;
  for (int n = 0; n < p.duration_count; ++n) {
    for (int i = 0; i < p.start_counts[0]; ++i) {
      for (int j = 0; j < p.start_counts[1]; ++j) {
        for (int l = 0; l < p.start_counts[2]; ++l) {
          const Eigen::Vector3d start = planner.StartPosition(target, i, j, l);
          const ApproachCandidate c = planner.EvaluateCandidate(target, start, planner.Duration(n));
          ++total;
          cheapest_any = std::min(cheapest_any, c.cost);
          below_floor += c.above_floor ? 0 : 1;
          if (!c.IsValid()) continue;
          ++valid;
          if (c.cost < best_cost) {
            best_cost = c.cost;
            best_start = start;
            best_duration = planner.Duration(n);
          }
        }
      }
    }
  }
  ASSERT_GT(valid, 0);
  EXPECT_LT(valid, total);
  EXPECT_LT(cheapest_any, best_cost);  // feasibility matters for the choice
  EXPECT_GT(below_floor, 0);

  const ApproachPlan plan = planner.Plan(target);
  std::ostringstream printed;
  printed << plan;
  ASSERT_TRUE(plan.best.has_value()) << printed.str();
  EXPECT_EQ(plan.candidates, total);
  EXPECT_LE(plan.feasibility_tests, total);
  EXPECT_EQ(plan.best->cost, best_cost) << printed.str();
  EXPECT_EQ(plan.best->primitive.duration_s(), best_duration);
  EXPECT_LT((plan.best->primitive.initial_position_W() - best_start).norm(), 1e-12);
  EXPECT_TRUE(plan.best->IsValid());
  // The chosen approach ends exactly in the traverse start state (1e-9, primitive test).
  const double T = plan.best->primitive.duration_s();
  EXPECT_LT((plan.best->primitive.Position(T) - target.p_W).norm(), 1e-9);
  EXPECT_LT((plan.best->primitive.Velocity(T) - target.v_W).norm(), 1e-9);
  EXPECT_LT((plan.best->primitive.Acceleration(T) - target.a_W).norm(), 1e-9);
}

// Samples carry the perception-aware heading: the camera axis of the resulting attitude is at the
// minimum view angle (9) from the gap centre.
TEST(ApproachPlanner, SampledHeadingKeepsTheGapCentred) {
  const ApproachTarget target = TestTarget();
  const ApproachPlanner planner(SmallGrid());
  const ApproachPlan plan = planner.Plan(target);
  ASSERT_TRUE(plan.best.has_value());
  const MotionPrimitive& primitive = plan.best->primitive;
  const double g = planner.parameters().limits.gravity_mps2;
  double sum_sq = 0.0;
  const int n = planner.parameters().samples_per_candidate;
  for (int s = 0; s < n; ++s) {
    const double t = primitive.duration_s() * s / (n - 1);
    const control::TrajectoryPoint point = planner.Sample(primitive, target.gap_center_W, t);
    const Eigen::Vector3d z_B = (point.a_W + Eigen::Vector3d(0, 0, g)).normalized();
    const Eigen::Vector3d d = target.gap_center_W - point.p_W;
    const Eigen::Vector3d axis_W = AttitudeFromHeading(z_B, point.heading_rad) *
                                   planner.parameters().optical_axis_B.normalized();
    const double angle = AngleBetween(axis_W, d);
    EXPECT_NEAR(angle, MinimumViewAngle(d, z_B, 0.0), 1e-9);
    sum_sq += angle * angle;
    EXPECT_TRUE(std::isfinite(point.heading_rate_radps) && std::isfinite(point.heading_acc_radps2));
  }
  // theta_rms of the candidate is the RMS over the same samples (1e-12: same arithmetic).
  EXPECT_NEAR(plan.best->view_angle_rms_rad, std::sqrt(sum_sq / n), 1e-9);
  // Heading rate agrees with a wider central difference of the heading (5 ms step: the heading
  // is smooth, the difference of the two estimates is O(h^2 psi''') << 1e-3 rad/s).
  const double t = 0.5 * primitive.duration_s(), h = 5e-3;
  const double rate =
      std::remainder(planner.Sample(primitive, target.gap_center_W, t + h).heading_rad -
                         planner.Sample(primitive, target.gap_center_W, t - h).heading_rad,
                     2.0 * kPi) /
      (2.0 * h);
  EXPECT_NEAR(planner.Sample(primitive, target.gap_center_W, t).heading_rate_radps, rate, 1e-3);
}

// The approach hands over to the traverse without a heading jump: its perception-aware heading at
// T (camera on the gap centre, thrust along the traverse's) equals the traverse's constant heading
// (1e-9 rad: the same direction computed through two formulas).
TEST(ApproachPlanner, EndsOnTheTraverseHeading) {
  const TraverseOptimizationResult traverse = OptimizeTraverseTrajectory(TestGap(), {});
  ASSERT_TRUE(traverse.trajectory.has_value());
  const ApproachTarget target = ApproachTarget::FromTraverse(*traverse.trajectory);
  const ApproachPlanner planner(SmallGrid());
  const ApproachPlan plan = planner.Plan(target);
  ASSERT_TRUE(plan.best.has_value());
  const double T = plan.best->primitive.duration_s();
  const control::TrajectoryPoint end = planner.Sample(plan.best->primitive, target.gap_center_W, T);
  EXPECT_NEAR(std::remainder(end.heading_rad - traverse.trajectory->heading_rad(), 2.0 * kPi), 0.0,
              1e-9);
  const control::TrajectoryPoint start = traverse.trajectory->Sample(0.0);
  EXPECT_LT((end.p_W - start.p_W).norm(), 1e-9);
  EXPECT_LT((end.v_W - start.v_W).norm(), 1e-9);
  EXPECT_LT((end.a_W - start.a_W).norm(), 1e-9);
}

// Replanning from a state on the plan with the remaining time reproduces the plan (the tail of a
// minimum-jerk primitive with fixed end state is the minimum-jerk primitive of the tail problem).
TEST(ApproachPlanner, ReplanFromThePlannedStateReproducesThePlan) {
  const ApproachTarget target = TestTarget();
  const ApproachPlanner planner(SmallGrid());
  const ApproachPlan plan = planner.Plan(target);
  ASSERT_TRUE(plan.best.has_value());
  const MotionPrimitive& primitive = plan.best->primitive;
  const double tau = 0.4 * primitive.duration_s();
  const ApproachCandidate replan =
      planner.Replan(target, primitive.Position(tau), primitive.Velocity(tau),
                     primitive.Acceleration(tau), primitive.duration_s() - tau);
  EXPECT_EQ(replan.feasibility, Feasibility::kFeasible);
  EXPECT_TRUE(replan.IsValid());
  for (double s = 0.0; s <= primitive.duration_s() - tau; s += 0.05) {
    // 1e-9 m: coefficient rounding of O(1) trajectories.
    EXPECT_LT((replan.primitive.Position(s) - primitive.Position(tau + s)).norm(), 1e-9);
  }
  EXPECT_THROW(planner.Replan(target, target.p_W, target.v_W, target.a_W, 0.0),
               std::invalid_argument);
}

// A state a gust pushed towards the gap with time to spare: the replan from it swings past the
// traverse start and comes back, which the planner refuses (the flag agrees with a dense sampling
// of the primitive's distance along traverse start -> gap centre); the replan from the planned
// state stays short of the start, and so does every candidate of a plan.
TEST(ApproachPlanner, RefusesAReplanThatPassesTheTraverseStart) {
  const ApproachTarget target = TestTarget();
  const ApproachPlanner planner(SmallGrid());
  const Eigen::Vector3d u_W = (target.gap_center_W - target.p_W).normalized();
  const double max_overshoot_m = planner.parameters().max_overshoot_m;
  const auto farthest_along_u = [&](const MotionPrimitive& primitive) {
    double farthest = -1e300;
    for (int k = 0; k <= 2000; ++k) {
      const double t = primitive.duration_s() * k / 2000.0;
      farthest = std::max(farthest, u_W.dot(primitive.Position(t) - target.p_W));
    }
    return farthest;
  };
  const Eigen::Vector3d pushed_p_W = target.p_W - 0.3 * u_W;  // 0.3 m short of the start ...
  const Eigen::Vector3d pushed_v_W = 1.5 * u_W;               // ... and heading for the gap
  const ApproachCandidate pushed =
      planner.Replan(target, pushed_p_W, pushed_v_W, Eigen::Vector3d::Zero(), 2.5);
  EXPECT_GT(farthest_along_u(pushed.primitive), max_overshoot_m);
  EXPECT_FALSE(pushed.short_of_target);
  EXPECT_FALSE(pushed.IsValid());

  const ApproachPlan plan = planner.Plan(target);
  ASSERT_TRUE(plan.best.has_value());
  EXPECT_TRUE(plan.best->short_of_target);
  EXPECT_LE(farthest_along_u(plan.best->primitive), max_overshoot_m);
  const MotionPrimitive& primitive = plan.best->primitive;
  const double tau = 0.5 * primitive.duration_s();
  const ApproachCandidate on_plan =
      planner.Replan(target, primitive.Position(tau), primitive.Velocity(tau),
                     primitive.Acceleration(tau), primitive.duration_s() - tau);
  EXPECT_TRUE(on_plan.short_of_target);
}

TEST(ApproachPlanner, RejectsBadParameters) {
  ApproachPlannerParameters parameters;
  parameters.duration_count = 0;
  EXPECT_THROW(ApproachPlanner{parameters}, std::invalid_argument);
  parameters = ApproachPlannerParameters();
  parameters.optical_axis_B = Eigen::Vector3d::UnitZ();
  EXPECT_THROW(ApproachPlanner{parameters}, std::invalid_argument);
  parameters = ApproachPlannerParameters();
  parameters.start_offset_max_A.x() = 0.0;  // below the minimum
  EXPECT_THROW(ApproachPlanner{parameters}, std::invalid_argument);
  parameters = ApproachPlannerParameters();
  parameters.max_overshoot_m = -0.1;
  EXPECT_THROW(ApproachPlanner{parameters}, std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
