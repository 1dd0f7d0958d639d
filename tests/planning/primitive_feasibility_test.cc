#include "planning/primitive_feasibility.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace aperture::planning {
namespace {

// Inputs by differential flatness, sampled densely: f = |a + g z|, |omega_xy| = |j_perp| / f with
// j_perp the jerk normal to the thrust direction (the exact body-rate magnitude for zero yaw rate),
// and the note's bound |j| / f >= |omega_xy|.
struct SampledInputs {
  double f_min = 1e300, f_max = 0.0, omega_max = 0.0, omega_bound_max = 0.0;
  double jerk_max = 0.0;  // max |j| over the samples, for the sampling-gap bound on f
};

SampledInputs SampleInputs(const MotionPrimitive& primitive, double gravity, int samples) {
  SampledInputs out;
  for (int k = 0; k <= samples; ++k) {
    const double t = primitive.duration_s() * k / samples;
    const Eigen::Vector3d c = primitive.Acceleration(t) + Eigen::Vector3d(0.0, 0.0, gravity);
    const Eigen::Vector3d j = primitive.Jerk(t);
    const double f = c.norm();
    out.f_min = std::min(out.f_min, f);
    out.f_max = std::max(out.f_max, f);
    out.jerk_max = std::max(out.jerk_max, j.norm());
    if (f > 0.0) {
      const Eigen::Vector3d z = c / f;
      out.omega_max = std::max(out.omega_max, (j - j.dot(z) * z).norm() / f);
      out.omega_bound_max = std::max(out.omega_bound_max, j.norm() / f);
    }
  }
  return out;
}

// 10,000 random primitives; every "feasible" verdict is confirmed by 1001
// samples (margins 1e-9: the verdict's bounds are exact inequalities, the samples only add
// rounding), and every "infeasible" verdict is confirmed by a sampled violation up to the
// sampling gap |df/dt| * dt / 2 <= |j|max * dt / 2 (|df/dt| <= |j| since f = |c|, dc/dt = j).
TEST(PrimitiveFeasibility, NeverCallsAnInfeasiblePrimitiveFeasible) {
  FeasibilityLimits limits;
  limits.min_thrust_mps2 = 5.0;
  limits.max_thrust_mps2 = 25.0;
  limits.max_body_rate_radps = 8.0;
  limits.Validate();
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> position(-4.0, 4.0), velocity(-3.0, 3.0),
      acceleration(-6.0, 6.0), duration(0.3, 4.0);
  auto vec = [&](std::uniform_real_distribution<double>& d) {
    return Eigen::Vector3d(d(rng), d(rng), d(rng));
  };
  const int samples = 1000;
  int counts[4] = {0, 0, 0, 0};
  for (int n = 0; n < 10000; ++n) {
    const MotionPrimitive primitive(vec(position), vec(velocity), vec(acceleration), vec(position),
                                    vec(velocity), vec(acceleration), duration(rng));
    const Feasibility verdict = CheckInputFeasibility(primitive, limits);
    ++counts[static_cast<int>(verdict)];
    const SampledInputs inputs = SampleInputs(primitive, limits.gravity_mps2, samples);
    const double gap = inputs.jerk_max * primitive.duration_s() / samples / 2.0 + 1e-9;
    switch (verdict) {
      case Feasibility::kFeasible:
        ASSERT_LE(inputs.f_max, limits.max_thrust_mps2 + 1e-9) << "case " << n;
        ASSERT_GE(inputs.f_min, limits.min_thrust_mps2 - 1e-9) << "case " << n;
        ASSERT_LE(inputs.omega_max, limits.max_body_rate_radps + 1e-9) << "case " << n;
        ASSERT_LE(inputs.omega_bound_max, limits.max_body_rate_radps + 1e-9) << "case " << n;
        break;
      case Feasibility::kInfeasibleThrustHigh:
        ASSERT_GT(inputs.f_max, limits.max_thrust_mps2 - gap) << "case " << n;
        break;
      case Feasibility::kInfeasibleThrustLow:
        ASSERT_LT(inputs.f_min, limits.min_thrust_mps2 + gap) << "case " << n;
        break;
      case Feasibility::kIndeterminable:
        break;
    }
  }
  // The random set exercises every verdict, so the checks above are not vacuous.
  for (int v = 0; v < 4; ++v) {
    EXPECT_GT(counts[v], 100) << ToString(static_cast<Feasibility>(v));
  }
}

// A gentle hover-to-hover move is feasible; the same move in 0.3 s needs more thrust than f_max
// allows, and a fall faster than gravity needs negative thrust.
TEST(PrimitiveFeasibility, KnownVerdicts) {
  const FeasibilityLimits limits;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  EXPECT_EQ(
      CheckInputFeasibility(
          MotionPrimitive(zero, zero, zero, Eigen::Vector3d(2, 1, 0.5), zero, zero, 3.0), limits),
      Feasibility::kFeasible);
  EXPECT_EQ(
      CheckInputFeasibility(
          MotionPrimitive(zero, zero, zero, Eigen::Vector3d(3, 0, 0), zero, zero, 0.3), limits),
      Feasibility::kInfeasibleThrustHigh);
  // An end acceleration of -1.5 g needs f(T) = 0.5 g = 4.9 < f_min = 5.
  EXPECT_EQ(CheckInputFeasibility(MotionPrimitive(zero, zero, zero, zero, zero,
                                                  Eigen::Vector3d(0, 0, -1.5 * 9.81), 2.0),
                                  limits),
            Feasibility::kInfeasibleThrustLow);
}

// The exact minimum of <n, p(t)> against 5,001 samples on 1,000 random primitives and normals:
// never above any sample (1e-12 rounding), and within the sampling gap of the sampled minimum
// (|d<n,p>/dt| * dt, bounded here by max |v| * dt).
TEST(PrimitiveFeasibility, MinimumProjectionMatchesDenseSampling) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-3.0, 3.0), duration(0.2, 4.0);
  auto vec = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  int interior_minima = 0;
  for (int n = 0; n < 1000; ++n) {
    const MotionPrimitive primitive(vec(), vec(), vec(), vec(), vec(), vec(), duration(rng));
    const Eigen::Vector3d normal = vec().normalized();
    const double exact = MinimumProjection(primitive, normal);
    const int samples = 5000;
    double sampled = 1e300, speed = 0.0;
    for (int k = 0; k <= samples; ++k) {
      const double t = primitive.duration_s() * k / samples;
      sampled = std::min(sampled, normal.dot(primitive.Position(t)));
      speed = std::max(speed, primitive.Velocity(t).norm());
    }
    ASSERT_LE(exact, sampled + 1e-12) << "case " << n;
    ASSERT_GE(exact, sampled - speed * primitive.duration_s() / samples - 1e-12) << "case " << n;
    const double ends = std::min(normal.dot(primitive.Position(0.0)),
                                 normal.dot(primitive.Position(primitive.duration_s())));
    if (exact < ends - 1e-6) ++interior_minima;
  }
  EXPECT_GT(interior_minima, 100);  // the interior root finding is exercised
}

TEST(PrimitiveFeasibility, LimitsFromVehicleAndValidation) {
  const control::VehicleParameters vehicle;
  const FeasibilityLimits limits = FeasibilityLimits::FromVehicle(vehicle, 10.0);
  EXPECT_NEAR(limits.max_thrust_mps2, 4.0 * vehicle.rotor.MaxThrust() / vehicle.mass_kg, 1e-12);
  EXPECT_NEAR(limits.min_thrust_mps2, 4.0 * vehicle.rotor.MinThrust() / vehicle.mass_kg, 1e-12);
  FeasibilityLimits bad;
  bad.max_thrust_mps2 = 1.0;  // below f_min
  EXPECT_THROW(bad.Validate(), std::invalid_argument);
  bad = FeasibilityLimits();
  bad.min_section_duration_s = 0.0;
  EXPECT_THROW(bad.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
