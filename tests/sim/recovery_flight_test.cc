// Hand throws recovered in the SITL by RecoveryAutopilot (thesis B.4): the five stages in order,
// a level, still hover at the end, all from the simulated IMU and range sensor.
#include "sim/sitl/recovery_flight.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "control/constants.h"

namespace aperture::sim {
namespace {

using control::kPi;

TEST(RecoveryFlightTest, SampledThrowsAreDeterministicAndWithinTheRanges) {
  HandThrowRanges ranges;
  double max_tilt = 0.0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const HandThrow a = SampleHandThrow(seed, ranges);
    const HandThrow b = SampleHandThrow(seed, ranges);
    EXPECT_TRUE(a.q_WB.isApprox(b.q_WB) && a.v_W == b.v_W && a.omega_B == b.omega_B);
    const double tilt = std::acos(std::clamp((a.q_WB * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0));
    max_tilt = std::max(max_tilt, tilt);
    EXPECT_LE(a.v_W.head<2>().norm(), ranges.max_horizontal_speed_mps + 1e-12);
    EXPECT_GE(a.v_W.z(), ranges.min_up_speed_mps);
    EXPECT_LE(a.v_W.z(), ranges.max_up_speed_mps);
    EXPECT_LE(a.omega_B.norm(), ranges.max_rate_radps + 1e-12);
  }
  // 200 uniform tilts in [0, pi]: the largest is near upside-down (P(max < 0.9 pi) = 0.9^200).
  EXPECT_GT(max_tilt, 0.9 * kPi);
}

// The hand's throw ends at the release: its acceleration integrates to the release velocity, its
// rates to the release attitude, and its peak acceleration is the minimum-jerk profile's.
TEST(RecoveryFlightTest, HandMotionEndsAtTheReleaseState) {
  HandThrow release;
  release.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized()));
  release.v_W = Eigen::Vector3d(2.0, -1.0, 3.0);
  release.omega_B = Eigen::Vector3d(4.0, -6.0, 8.0);
  const double throw_s = 0.25;
  const int steps = 25000;
  const double dt_s = throw_s / steps;
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_WB = HandMotionAt(release, throw_s, -throw_s).q_WB;
  double peak_mps2 = 0.0;
  for (int k = 0; k < steps; ++k) {
    const HandMotion mid = HandMotionAt(release, throw_s, -throw_s + (k + 0.5) * dt_s);
    v_W += mid.a_W * dt_s;
    q_WB = q_WB * Eigen::AngleAxisd(mid.omega_B.norm() * dt_s, mid.omega_B.normalized());
    peak_mps2 = std::max(peak_mps2, mid.a_W.norm());
  }
  EXPECT_LT((v_W - release.v_W).norm(), 1e-6);
  EXPECT_LT(q_WB.angularDistance(release.q_WB), 1e-6);
  EXPECT_NEAR(peak_mps2, 1.875 * release.v_W.norm() / throw_s, 1e-3);
  EXPECT_TRUE(HandMotionAt(release, throw_s, 0.0).omega_B.isApprox(release.omega_B));
  EXPECT_EQ(HandMotionAt(release, throw_s, 0.0).a_W.norm(), 0.0);
}

// B.4.2's failure mode: near the ground at speed the vision pipeline cannot initialize (the
// ground's image flow blurs its features) until the drag has slowed the drifting vehicle; the same
// throw released higher initializes sooner.
TEST(RecoveryFlightTest, LowAndFastThrowsInitializeTheVisionLater) {
  const auto vision_time_s = [](double release_height_m) {
    RecoveryFlightParams params;
    params.p_release_W.z() = release_height_m;
    params.hand_throw.v_W = Eigen::Vector3d(4.0, 0.0, 0.0);
    params.duration_s = 8.0;
    const RecoveryFlightResult flight = FlyRecoveryFlight(params);
    EXPECT_NE(flight.outcome, "crashed") << release_height_m << " m: " << flight.sitl.reason;
    return flight.vision_available_s < 0.0 ? params.duration_s : flight.vision_available_s;
  };
  const double low_s = vision_time_s(0.6);
  const double high_s = vision_time_s(2.5);
  EXPECT_GT(low_s, high_s + 0.5) << "low " << low_s << " s, high " << high_s << " s";
}

class RecoveryFlightHeadingTest : public ::testing::TestWithParam<double> {};

// The IMU estimator's heading is arbitrary; the emulated vision frame must share it, else the
// horizontal feedback is rotated by the heading error (unstable beyond 90 deg). Headings 0 and
// 2.5 rad.
TEST_P(RecoveryFlightHeadingTest, UpsideDownThrowEndsInAStableHover) {
  RecoveryFlightParams params;
  params.hand_throw.q_WB = Eigen::AngleAxisd(0.9 * kPi, Eigen::Vector3d::UnitY()) *
                           Eigen::AngleAxisd(GetParam(), Eigen::Vector3d::UnitZ());
  params.hand_throw.v_W = Eigen::Vector3d(-1.5, 2.5, 3.0);
  params.hand_throw.omega_B = Eigen::Vector3d(-3.0, 5.0, -6.0);
  const RecoveryFlightResult flight = FlyRecoveryFlight(params);
  EXPECT_EQ(flight.outcome, "recovered") << flight.sitl.reason;
  ASSERT_EQ(flight.transitions.size(), 5u);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(static_cast<int>(flight.transitions[k].to), k + 1);
  // Launch detected within the 50 ms window after the release at t = 0 (B.29), plus a sample,
  // and not in the hand while it throws.
  EXPECT_LT(flight.transitions[0].t_s, 0.06);
  EXPECT_GE(flight.launch_detected_s, 0.0);
  EXPECT_LT(flight.launch_detected_s, 0.06);
  // The vision pipeline initialized in the height stage (3) and before the braking stage (4).
  EXPECT_GE(flight.vision_available_s, flight.transitions[2].t_s);
  EXPECT_LE(flight.vision_available_s, flight.transitions[3].t_s);
  EXPECT_GT(flight.min_height_m, 0.3);
  // Measured: level within 1 deg, < 3 cm/s. After hold_s = 4 s of position control: level (< 3 deg)
  // and still (< 0.1 m/s).
  EXPECT_LT(flight.final_tilt_rad, 3.0 * kPi / 180.0);
  EXPECT_LT(flight.final_speed_mps, 0.1);
}

INSTANTIATE_TEST_SUITE_P(Headings, RecoveryFlightHeadingTest, ::testing::Values(0.0, 2.5));

}  // namespace
}  // namespace aperture::sim
