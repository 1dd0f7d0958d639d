#include "control/reference_trajectories.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

namespace aperture::control {
namespace {

struct DerivativeCheck {
  double max_v = 0.0, max_a = 0.0, max_j = 0.0, max_s = 0.0;
};

// Central differences of each level against the analytic next level, relative to the scale of
// the differentiated quantity's derivative (so metre- and 100 m/s^4-sized signals share a bound).
DerivativeCheck CompareWithCentralDifferences(const ReferenceTrajectory& trajectory,
                                              const std::vector<double>& times) {
  const double h = 1e-5;
  DerivativeCheck check;
  for (double t : times) {
    const TrajectoryPoint p = trajectory.Evaluate(t);
    const TrajectoryPoint plus = trajectory.Evaluate(t + h);
    const TrajectoryPoint minus = trajectory.Evaluate(t - h);
    auto error = [&](const Eigen::Vector3d& up, const Eigen::Vector3d& down,
                     const Eigen::Vector3d& analytic) {
      return ((up - down) / (2.0 * h) - analytic).norm() / (1.0 + analytic.norm());
    };
    check.max_v = std::max(check.max_v, error(plus.p_W, minus.p_W, p.v_W));
    check.max_a = std::max(check.max_a, error(plus.v_W, minus.v_W, p.a_W));
    check.max_j = std::max(check.max_j, error(plus.a_W, minus.a_W, p.j_W));
    check.max_s = std::max(check.max_s, error(plus.j_W, minus.j_W, p.s_W));
  }
  return check;
}

std::vector<double> Times(double begin, double end, double step) {
  std::vector<double> times;
  for (double t = begin; t < end; t += step) times.push_back(t);
  return times;
}

void ExpectDerivativesConsistent(const ReferenceTrajectory& trajectory,
                                 const std::vector<double>& times) {
  const DerivativeCheck check = CompareWithCentralDifferences(trajectory, times);
  // h = 1e-5: truncation h^2 |x'''| / 6 < 1e-8 for these signals, round-off 1e-16 |x| / h < 1e-9.
  EXPECT_LT(check.max_v, 1e-7);
  EXPECT_LT(check.max_a, 1e-7);
  EXPECT_LT(check.max_j, 1e-7);
  EXPECT_LT(check.max_s, 1e-7);
}

TEST(ReferenceTrajectoriesTest, CircleDerivativesMatchNumericDifferencesInEveryPhase) {
  const CircleTrajectory circle;
  // Ramp-in [0, 3), cruise, ramp-out, rest; sample across all of them (off the piece borders).
  ExpectDerivativesConsistent(circle, Times(0.013, circle.EndTimeS() + 2.0, 0.07));
}

TEST(ReferenceTrajectoriesTest, CircleFliesRadiusAndSpeedOfThesisAndStopsAtRest) {
  const CircleTrajectoryParams params;
  const CircleTrajectory circle(params);
  const TrajectoryPoint start = circle.Evaluate(0.0);
  EXPECT_LT((start.p_W - (params.center_W + Eigen::Vector3d(1.8, 0, 0))).norm(), 1e-12);
  EXPECT_EQ(start.v_W.norm(), 0.0);  // starts from rest
  double max_speed = 0.0;
  for (double t = 0.0; t < circle.EndTimeS(); t += 0.01) {
    const TrajectoryPoint p = circle.Evaluate(t);
    EXPECT_NEAR((p.p_W - params.center_W).norm(), 1.8, 1e-12);
    max_speed = std::max(max_speed, p.v_W.norm());
    if (t > 3.0 && t < circle.EndTimeS() - 3.0) {
      EXPECT_NEAR(p.v_W.norm(), 4.0, 1e-12);
    }
  }
  EXPECT_NEAR(max_speed, 4.0, 1e-12);
  // Ramp-out ends at rest, with every derivative zero (continuous in snap).
  const TrajectoryPoint end = circle.Evaluate(circle.EndTimeS() + 1.0);
  EXPECT_EQ(end.v_W.norm() + end.a_W.norm() + end.j_W.norm() + end.s_W.norm(), 0.0);
  // Ten loops at full speed plus half a loop's length in each ramp: the phase at the end.
  const double loops = 10.0 + 2.0 * (0.5 * 3.0 * 4.0 / 1.8) / (2.0 * M_PI);
  const Eigen::Vector3d expected_end =
      params.center_W +
      1.8 * Eigen::Vector3d(std::cos(2.0 * M_PI * loops), std::sin(2.0 * M_PI * loops), 0.0);
  EXPECT_LT((end.p_W - expected_end).norm(), 1e-9);
}

TEST(ReferenceTrajectoriesTest, SmoothRampIsContinuousInSnapAtPieceBorders) {
  const CircleTrajectory circle;
  for (double border : {3.0, circle.EndTimeS() - 3.0, circle.EndTimeS()}) {
    const TrajectoryPoint before = circle.Evaluate(border - 1e-9);
    const TrajectoryPoint after = circle.Evaluate(border + 1e-9);
    // Every level changes by at most its next derivative times 2e-9 s.
    EXPECT_LT((before.p_W - after.p_W).norm(), 1e-7);
    EXPECT_LT((before.v_W - after.v_W).norm(), 1e-7);
    EXPECT_LT((before.a_W - after.a_W).norm(), 1e-7);
    EXPECT_LT((before.j_W - after.j_W).norm(), 1e-6);
    EXPECT_LT((before.s_W - after.s_W).norm(), 1e-6);
  }
}

TEST(ReferenceTrajectoriesTest, LemniscateMatchesThesisDefinitionAtFullSpeed) {
  LemniscateTrajectoryParams params;
  params.center_W.setZero();
  params.ramp.num_loops = 3.0;
  const LemniscateTrajectory lemniscate(params);
  ExpectDerivativesConsistent(lemniscate, Times(0.013, lemniscate.EndTimeS() + 1.0, 0.07));
  // During cruise phi = sqrt(2) t + const, so x = 2 cos(phi) and y = 2 sin(phi) cos(phi) =
  // sin(2 phi) (F.7.2) obey x'' = -2 x and y'' = -8 y, and the curve A^2 y^2 = x^2 (A^2 - x^2).
  for (double t = 3.1; t < lemniscate.EndTimeS() - 3.1; t += 0.1) {
    const TrajectoryPoint p = lemniscate.Evaluate(t);
    EXPECT_NEAR(p.a_W.x(), -2.0 * p.p_W.x(), 1e-12);
    EXPECT_NEAR(p.a_W.y(), -8.0 * p.p_W.y(), 1e-12);
    const double x2 = p.p_W.x() * p.p_W.x();
    EXPECT_NEAR(4.0 * p.p_W.y() * p.p_W.y(), x2 * (4.0 - x2), 1e-12);
  }
  double max_speed = 0.0;
  for (double t = 3.0; t < 3.0 + 2.0 * M_PI / std::sqrt(2.0); t += 1e-3) {
    max_speed = std::max(max_speed, lemniscate.Evaluate(t).v_W.norm());
  }
  EXPECT_NEAR(max_speed, 4.0, 1e-5);  // sampled peak: 1e-3 s steps around a smooth maximum
}

TEST(ReferenceTrajectoriesTest, ThesisSpeedRampReachesFiveMetresPerSecondAfterThirtySeconds) {
  const CircleTrajectory circle(CircleTrajectoryParams::ThesisSpeedRamp());
  EXPECT_NEAR(circle.Evaluate(15.0).v_W.norm(), 2.5, 1e-12);  // linear in time
  EXPECT_NEAR(circle.Evaluate(30.0).v_W.norm(), 5.0, 1e-12);
  EXPECT_NEAR(circle.Evaluate(45.0).v_W.norm(), 5.0, 1e-12);
  EXPECT_TRUE(std::isinf(circle.EndTimeS()));
  // Away from the two corners (t = 0 and t = 30 s) the derivatives are exact.
  ExpectDerivativesConsistent(circle, Times(0.5, 29.5, 0.61));
  ExpectDerivativesConsistent(circle, Times(30.5, 40.0, 0.61));

  const LemniscateTrajectory lemniscate(LemniscateTrajectoryParams::ThesisSpeedRamp());
  double max_speed = 0.0;
  for (double t = 30.0; t < 30.0 + 2.0 * M_PI / (5.0 / (2.0 * std::sqrt(2.0))); t += 1e-3) {
    max_speed = std::max(max_speed, lemniscate.Evaluate(t).v_W.norm());
  }
  EXPECT_NEAR(max_speed, 5.0, 1e-5);
  ExpectDerivativesConsistent(lemniscate, Times(0.5, 29.5, 0.61));
}

TEST(ReferenceTrajectoriesTest, BackAndForthHitsThesisPeaksAndIsContinuousInSnap) {
  const BackAndForthTrajectoryParams params;
  const BackAndForthTrajectory trajectory(params);
  EXPECT_NEAR(trajectory.SegmentDurationS(), 1.809, 1e-3);
  EXPECT_NEAR(trajectory.SegmentLengthM(), 4.190, 1e-3);
  double max_speed = 0.0, max_accel = 0.0, min_x = 1e9, max_x = -1e9;
  // The first round trip and a bit of the next one (all segments are the same polynomial).
  for (double t = -1.0; t < 3.0 * trajectory.SegmentDurationS(); t += 1e-4) {
    const TrajectoryPoint p = trajectory.Evaluate(t);
    max_speed = std::max(max_speed, p.v_W.norm());
    max_accel = std::max(max_accel, p.a_W.norm());
    min_x = std::min(min_x, p.p_W.x());
    max_x = std::max(max_x, p.p_W.x());
    EXPECT_EQ(p.v_W.y(), 0.0);
    EXPECT_EQ(p.p_W.z(), params.start_W.z());
  }
  // 1e-4 s sampling around smooth maxima: relative error below 1e-6.
  EXPECT_NEAR(max_speed, 5.7, 1e-5);
  EXPECT_NEAR(max_accel, 12.0, 1e-5);
  EXPECT_NEAR(min_x, params.start_W.x(), 1e-12);
  EXPECT_NEAR(max_x, params.start_W.x() + trajectory.SegmentLengthM(), 1e-9);
  // Segment borders: every derivative up to snap vanishes on both sides.
  const double T = trajectory.SegmentDurationS();
  for (int k = 1; k < 4; ++k) {
    for (double t : {k * T - 1e-9, k * T + 1e-9}) {
      const TrajectoryPoint p = trajectory.Evaluate(t);
      EXPECT_LT(p.v_W.norm(), 1e-9);
      // Snap leaves zero linearly: 5th derivative 15120 L / T^5 ~ 3e3 m/s^5 times 1e-9 s.
      EXPECT_LT(p.s_W.norm(), 1e-5);
    }
  }
  ExpectDerivativesConsistent(trajectory, Times(0.011, 4.0 * T, 0.037));
  // After the last round trip the vehicle rests at the start.
  const TrajectoryPoint end = trajectory.Evaluate(trajectory.EndTimeS() + 0.5);
  EXPECT_LT((end.p_W - params.start_W).norm(), 1e-12);
}

TEST(ReferenceTrajectoriesTest, BackAndForthWithDwellRestsBetweenSegments) {
  BackAndForthTrajectoryParams params;
  params.dwell_s = 0.5;
  params.num_round_trips = 2;
  const BackAndForthTrajectory trajectory(params);
  const double T = trajectory.SegmentDurationS();
  const TrajectoryPoint resting = trajectory.Evaluate(T + 0.25);
  EXPECT_NEAR(resting.p_W.x(), trajectory.SegmentLengthM(), 1e-12);
  EXPECT_EQ(resting.v_W.norm(), 0.0);
  EXPECT_NEAR(trajectory.EndTimeS(), 4.0 * (T + 0.5), 1e-12);
}

TEST(ReferenceTrajectoriesTest, InvalidParametersThrowNamingTheField) {
  CircleTrajectoryParams circle;
  circle.radius_m = -1.0;
  EXPECT_THROW(CircleTrajectory{circle}, std::invalid_argument);
  LemniscateTrajectoryParams lemniscate;
  lemniscate.ramp.ramp_s = 0.0;
  EXPECT_THROW(LemniscateTrajectory{lemniscate}, std::invalid_argument);
  BackAndForthTrajectoryParams back;
  back.max_accel_mps2 = 0.0;
  try {
    BackAndForthTrajectory{back};
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_accel_mps2"), std::string::npos) << e.what();
  }
}

TEST(ReferenceTrajectoriesTest, ThesisTrajectoriesByName) {
  const auto circle = MakeThesisTrajectory("circle");
  EXPECT_NEAR(circle->Evaluate(5.0).v_W.norm(), 4.0, 1e-12);
  const auto ramp = MakeThesisTrajectory("circle_speed_ramp");
  EXPECT_NEAR(ramp->Evaluate(30.0).v_W.norm(), 5.0, 1e-12);
  const auto lemniscate = MakeThesisTrajectory("lemniscate_speed_ramp");
  EXPECT_TRUE(std::isinf(lemniscate->EndTimeS()));
  const auto back = MakeThesisTrajectory("back_and_forth");
  EXPECT_NEAR(back->Evaluate(0.5 * 1.809).v_W.x(), 5.7, 1e-3);  // peak speed mid-segment
  EXPECT_NE(MakeThesisTrajectory("lemniscate"), nullptr);
  try {
    MakeThesisTrajectory("cirle");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'cirle'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("back_and_forth"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aperture::control
