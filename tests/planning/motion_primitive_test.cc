#include "planning/motion_primitive.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace aperture::planning {
namespace {

struct PrimitiveCase {
  Eigen::Vector3d p0, v0, a0, pf, vf, af;
  double T;
};

PrimitiveCase RandomCase(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::uniform_real_distribution<double> duration(0.2, 5.0);
  auto vec = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  return {vec(), vec(), vec(), vec(), vec(), vec(), duration(rng)};
}

class MotionPrimitiveEndTest : public ::testing::TestWithParam<EndConstraint> {};

// Every end constraint meets the initial state and its prescribed end components, and its free
// components satisfy the transversality conditions (j(T) = 0 if a is free, j'(T) = 0 if v is).
// Tolerance 1e-9 absolute on O(1) states: coefficients carry ~1e-14 relative rounding amplified by
// T^-5 and then multiplied back by T^5, leaving < 1e-11 in practice.
TEST_P(MotionPrimitiveEndTest, MeetsBoundaryConditions) {
  const EndConstraint end = GetParam();
  std::mt19937 rng(7);
  for (int n = 0; n < 200; ++n) {
    const PrimitiveCase c = RandomCase(rng);
    const MotionPrimitive primitive(c.p0, c.v0, c.a0, c.pf, c.vf, c.af, c.T, end);
    EXPECT_LT((primitive.Position(0.0) - c.p0).norm(), 1e-9);
    EXPECT_LT((primitive.Velocity(0.0) - c.v0).norm(), 1e-9);
    EXPECT_LT((primitive.Acceleration(0.0) - c.a0).norm(), 1e-9);
    EXPECT_LT((primitive.Position(c.T) - c.pf).norm(), 1e-9);
    const bool velocity_fixed = end == EndConstraint::kPositionVelocityAcceleration ||
                                end == EndConstraint::kPositionVelocity;
    const bool acceleration_fixed = end == EndConstraint::kPositionVelocityAcceleration ||
                                    end == EndConstraint::kPositionAcceleration;
    if (velocity_fixed) {
      EXPECT_LT((primitive.Velocity(c.T) - c.vf).norm(), 1e-9);
    } else {
      EXPECT_LT(primitive.Snap(c.T).norm(), 1e-9 * primitive.alpha().norm() + 1e-9);
    }
    if (acceleration_fixed) {
      EXPECT_LT((primitive.Acceleration(c.T) - c.af).norm(), 1e-9);
    } else {
      EXPECT_LT(primitive.Jerk(c.T).norm(), 1e-9 * primitive.alpha().norm() + 1e-9);
    }
  }
}

// The closed-form cost equals (1/T) int j^2 by Simpson's rule. j^2 is a quartic and Simpson's rule
// is exact for cubics; with 2000 panels the quartic error is ~T^4/n^4 |j''''|, < 1e-9 relative.
TEST_P(MotionPrimitiveEndTest, CostMatchesNumericalIntegralOfJerkSquared) {
  std::mt19937 rng(11);
  for (int n = 0; n < 50; ++n) {
    const PrimitiveCase c = RandomCase(rng);
    const MotionPrimitive primitive(c.p0, c.v0, c.a0, c.pf, c.vf, c.af, c.T, GetParam());
    const int panels = 2000;
    const double h = c.T / panels;
    double integral = 0.0;
    for (int k = 0; k <= panels; ++k) {
      const double weight = (k == 0 || k == panels) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
      integral += weight * primitive.Jerk(k * h).squaredNorm();
    }
    integral *= h / 3.0 / c.T;
    EXPECT_NEAR(primitive.Cost(), integral, 1e-9 * integral);
  }
}

// Optimality: adding any admissible perturbation (zero value and derivatives at both ends up to the
// constrained order) increases the cost, since the primitive is the unique minimiser.
TEST_P(MotionPrimitiveEndTest, PerturbationsDoNotLowerTheCost) {
  // The bump below vanishes with its first 3 derivatives at both ends, so it is admissible for
  // every end constraint.
  std::mt19937 rng(3);
  const PrimitiveCase c = RandomCase(rng);
  const MotionPrimitive primitive(c.p0, c.v0, c.a0, c.pf, c.vf, c.af, c.T, GetParam());
  const int panels = 4000;
  const double h = c.T / panels;
  for (double eps : {1e-2, -1e-2, 1e-1}) {
    double integral = 0.0;
    for (int k = 0; k <= panels; ++k) {
      const double t = k * h, s = t / c.T;
      // Position bump eps * b(t/T), b(s) = s^4 (1-s)^4 = s^4 - 4s^5 + 6s^6 - 4s^7 + s^8; its
      // jerk is eps * b'''(s) / T^3.
      const double b3_exact = (24.0 * s - 240.0 * s * s + 720.0 * s * s * s -
                               840.0 * s * s * s * s + 336.0 * s * s * s * s * s) /
                              (c.T * c.T * c.T);
      const double weight = (k == 0 || k == panels) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
      const Eigen::Vector3d j = primitive.Jerk(t) + Eigen::Vector3d::Constant(eps * b3_exact);
      integral += weight * j.squaredNorm();
    }
    integral *= h / 3.0 / c.T;
    EXPECT_GT(integral, primitive.Cost());
  }
}

INSTANTIATE_TEST_SUITE_P(AllEnds, MotionPrimitiveEndTest,
                         ::testing::Values(EndConstraint::kPositionVelocityAcceleration,
                                           EndConstraint::kPositionVelocity,
                                           EndConstraint::kPositionAcceleration,
                                           EndConstraint::kPosition));

// Derivatives are consistent: central differences of p, v, a, j match v, a, j, s.
TEST(MotionPrimitive, DerivativesAreConsistent) {
  std::mt19937 rng(5);
  const PrimitiveCase c = RandomCase(rng);
  const MotionPrimitive primitive(c.p0, c.v0, c.a0, c.pf, c.vf, c.af, c.T);
  const double h = 1e-5;
  for (double t : {0.1 * c.T, 0.5 * c.T, 0.9 * c.T}) {
    // Central difference error ~h^2 * |higher derivative| ~ 1e-10 * O(10^3) plus rounding
    // ~1e-16 * |p| / h ~ 1e-11: 1e-5 relative is safe.
    const auto fd = [&](auto f) { return ((f(t + h) - f(t - h)) / (2.0 * h)).eval(); };
    EXPECT_TRUE(
        fd([&](double s) { return primitive.Position(s); }).isApprox(primitive.Velocity(t), 1e-5));
    EXPECT_TRUE(fd([&](double s) {
                  return primitive.Velocity(s);
                }).isApprox(primitive.Acceleration(t), 1e-5));
    EXPECT_TRUE(
        fd([&](double s) { return primitive.Acceleration(s); }).isApprox(primitive.Jerk(t), 1e-5));
    EXPECT_TRUE(fd([&](double s) { return primitive.Jerk(s); }).isApprox(primitive.Snap(t), 1e-5));
  }
  const control::TrajectoryPoint point = primitive.Sample(0.3);
  EXPECT_EQ(point.t_s, 0.3);
  EXPECT_EQ(point.p_W, primitive.Position(0.3));
  EXPECT_EQ(point.s_W, primitive.Snap(0.3));
}

TEST(MotionPrimitive, RejectsBadDuration) {
  const Eigen::Vector3d z = Eigen::Vector3d::Zero();
  EXPECT_THROW(MotionPrimitive(z, z, z, z, z, z, 0.0), std::invalid_argument);
  EXPECT_THROW(MotionPrimitive(z, z, z, z, z, z, -1.0), std::invalid_argument);
  EXPECT_THROW(MotionPrimitive(z, z, z, z, z, z, std::nan("")), std::invalid_argument);
  EXPECT_THROW(MotionPrimitive(z, z, z, Eigen::Vector3d::Constant(std::nan("")), z, z, 1.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
