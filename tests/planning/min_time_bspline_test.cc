// Minimum-time quintic B-spline (seed 003 Sec. III-E): NLopt's time scaling equals the analytic
// optimum (the objective is convex and separable, so each chi_i sits on its tightest limit), the
// refit trajectory respects the v/a/j limits at every sample and saturates at least one of them,
// passes its end points with the requested end states, and the jerk bound is f_min w_max / sqrt(3).
#include "planning/mono_nav/min_time_bspline.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aperture::planning {
namespace {

// The Bezier-like sweep of a waypoint path: 10 points around a trunk, x forward, y lateral.
std::vector<Eigen::Vector3d> CurvedPath() {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 9; ++i) {
    const double s = i / 9.0;
    points.emplace_back(6.0 * s, 1.5 * std::sin(M_PI * s), 0.3 * s);
  }
  return points;
}

struct BsplineCase {
  const char* name;
  DynamicLimits limits;
  Eigen::Vector3d v0;
};

class MinTimeBSplineTest : public ::testing::TestWithParam<BsplineCase> {};

TEST_P(MinTimeBSplineTest, RespectsEveryLimitAtEverySampleAndSaturatesOne) {
  const BsplineCase& c = GetParam();
  const std::vector<Eigen::Vector3d> path = CurvedPath();
  const MinTimeBSplineResult result =
      PlanMinTimeBSpline(path, c.v0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                         Eigen::Vector3d::Zero(), c.limits);
  ASSERT_TRUE(result.ok()) << result;
  ASSERT_TRUE(result.trajectory.has_value());
  // NLopt found the analytic optimum of (21)-(30): chi_i at its tightest bound.
  for (std::size_t i = 0; i < result.chi.size(); ++i) {
    EXPECT_NEAR(result.chi[i], result.chi_bound[i], 1e-6 * result.chi_bound[i])
        << "interval " << i << " " << result;
  }
  // Limits at 2000 samples (5x denser than the planner's own check), with the tolerance of the
  // planner's check resolution: a sample between two checked ones may exceed by O(h^2).
  const BSpline& s = *result.trajectory;
  double speed = 0.0, acceleration = 0.0, jerk = 0.0;
  for (int k = 0; k <= 2000; ++k) {
    const double t = result.duration_s * k / 2000.0;
    speed = std::max(speed, s.Evaluate(t, 1).norm() / c.limits.max_speed_mps);
    acceleration = std::max(
        acceleration,
        s.Evaluate(t, 2).cwiseAbs().cwiseQuotient(c.limits.max_acceleration_mps2).maxCoeff());
    jerk = std::max(jerk,
                    s.Evaluate(t, 3).cwiseAbs().cwiseQuotient(c.limits.max_jerk_mps3).maxCoeff());
  }
  EXPECT_LE(speed, 1.0 + 1e-3) << result;
  EXPECT_LE(acceleration, 1.0 + 1e-3) << result;
  EXPECT_LE(jerk, 1.0 + 1e-3) << result;
  // Time optimality check of the paper: at least one limit is reached.
  EXPECT_GE(std::max({speed, acceleration, jerk}), 1.0 - 2e-3) << result;
  // End states and end points.
  EXPECT_LT((s.Evaluate(0.0) - path.front()).norm(), 1e-9);
  EXPECT_LT((s.Evaluate(result.duration_s) - path.back()).norm(), 1e-9);
  EXPECT_LT((s.Evaluate(0.0, 1) - c.v0).norm(), 1e-9);
  EXPECT_LT(s.Evaluate(result.duration_s, 1).norm(), 1e-9);
  EXPECT_LT(s.Evaluate(result.duration_s, 2).norm(), 1e-9);
  // No faster than flying the chord at full speed.
  EXPECT_GE(result.duration_s, (path.back() - path.front()).norm() / c.limits.max_speed_mps);
}

DynamicLimits Limits(double v, double a, double j) {
  DynamicLimits limits;
  limits.max_speed_mps = v;
  limits.max_acceleration_mps2.setConstant(a);
  limits.max_jerk_mps3.setConstant(j);
  return limits;
}

INSTANTIATE_TEST_SUITE_P(
    Limits, MinTimeBSplineTest,
    ::testing::Values(
        BsplineCase{"paper_fig6", Limits(1.3, 0.5, 0.5), Eigen::Vector3d::Zero()},
        BsplineCase{"speed_bound", Limits(1.0, 4.0, 20.0), Eigen::Vector3d::Zero()},
        BsplineCase{"jerk_bound", Limits(5.0, 5.0, DynamicLimits::JerkBound(5.0, 0.2)),
                    Eigen::Vector3d::Zero()},
        BsplineCase{"moving_start", Limits(2.0, 1.5, 3.0), Eigen::Vector3d(0.8, 0.0, 0.0)}),
    [](const ::testing::TestParamInfo<BsplineCase>& info) { return std::string(info.param.name); });

TEST(MinTimeBSpline, JerkBoundIsThrustTimesRateOverSqrt3) {
  EXPECT_NEAR(DynamicLimits::JerkBound(6.0, 3.0), 18.0 / std::sqrt(3.0), 1e-12);
  EXPECT_THROW(DynamicLimits::JerkBound(0.0, 3.0), std::invalid_argument);
}

TEST(MinTimeBSpline, RejectsBadInput) {
  const DynamicLimits limits;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> short_path(5, zero);
  EXPECT_THROW(PlanMinTimeBSpline(short_path, zero, zero, zero, zero, limits),
               std::invalid_argument);
  std::vector<Eigen::Vector3d> repeated = CurvedPath();
  repeated[3] = repeated[2];
  EXPECT_THROW(PlanMinTimeBSpline(repeated, zero, zero, zero, zero, limits), std::invalid_argument);
  EXPECT_THROW(PlanMinTimeBSpline(CurvedPath(), Eigen::Vector3d(5, 0, 0), zero, zero, zero, limits),
               std::invalid_argument);
  DynamicLimits bad = limits;
  bad.max_jerk_mps3.x() = 0.0;
  EXPECT_THROW(PlanMinTimeBSpline(CurvedPath(), zero, zero, zero, zero, bad),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
