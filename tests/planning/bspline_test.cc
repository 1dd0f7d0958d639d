// BSpline: basis functions sum to one, derivatives match central differences of the curve, a
// clamped spline starts and ends at its end control points, time scaling divides the k-th
// derivative by factor^k, and averaged knots interpolate (The NURBS Book (9.8)).
#include "planning/mono_nav/bspline.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aperture::planning {
namespace {

BSpline Example() {
  const int count = 9;
  std::vector<double> params;
  for (int i = 0; i < count; ++i) params.push_back(std::pow(i / 8.0, 1.3) * 2.0);
  BSpline::ControlPoints points(count, 3);
  for (int i = 0; i < count; ++i) points.row(i) << std::sin(i), 0.3 * i * i, std::cos(2.0 * i);
  return BSpline(5, BSpline::AveragedKnots(params, 5, count), points);
}

TEST(BSpline, BasisIsAPartitionOfUnityAndEndsAreClamped) {
  const BSpline s = Example();
  for (double t = 0.0; t <= 2.0; t += 0.01) EXPECT_NEAR(s.BasisRow(t, 0).sum(), 1.0, 1e-12);
  EXPECT_TRUE(s.Evaluate(0.0).isApprox(s.control_points().row(0).transpose(), 1e-12));
  EXPECT_TRUE(s.Evaluate(2.0).isApprox(s.control_points().bottomRows(1).transpose(), 1e-12));
}

TEST(BSpline, DerivativesMatchCentralDifferences) {
  const BSpline s = Example();
  const double h = 1e-5;
  for (double t = 0.05; t < 1.95; t += 0.0731) {
    for (int k = 1; k <= 3; ++k) {
      const Eigen::Vector3d numeric =
          (s.Evaluate(t + h, k - 1) - s.Evaluate(t - h, k - 1)) / (2 * h);
      EXPECT_TRUE(s.Evaluate(t, k).isApprox(numeric, 1e-5 * (1.0 + numeric.norm())))
          << "t " << t << " derivative " << k << ": " << s.Evaluate(t, k).transpose() << " vs "
          << numeric.transpose();
    }
  }
}

TEST(BSpline, TimeScalingDividesDerivativesByThePower) {
  const BSpline s = Example();
  const BSpline slow = s.TimeScaled(2.5);
  EXPECT_DOUBLE_EQ(slow.EndParameter(), 5.0);
  for (int k = 0; k <= 3; ++k) {
    EXPECT_TRUE(
        slow.Evaluate(2.5 * 0.77, k).isApprox(s.Evaluate(0.77, k) / std::pow(2.5, k), 1e-12));
  }
}

TEST(BSpline, RejectsUnclampedOrShortKnotVectors) {
  BSpline::ControlPoints points = BSpline::ControlPoints::Zero(6, 3);
  EXPECT_THROW(BSpline(5, {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1}, points), std::invalid_argument);
  EXPECT_THROW(BSpline(5, {0, 0, 0, 0, 0, 0.5, 1, 1, 1, 1, 1, 1}, points), std::invalid_argument);
  EXPECT_NO_THROW(BSpline(5, {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1}, points));
}

}  // namespace
}  // namespace aperture::planning
