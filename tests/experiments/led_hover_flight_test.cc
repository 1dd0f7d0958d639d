// LED-stabilized hover closed loop (issue 6, thesis C.4.3): the `led` scenario's ground camera
// renders the vehicle's 5 LEDs at 40 Hz with 25 ms latency, planning::LedHoverAutopilot holds
// the start from the LED pose + IMU only (ground truth never reaches it) through a gust and a
// push, and the ground-truth trajectory is scored. Plus ComputeHoverMetrics on analytic cases.
#include "experiments/led/led_hover_flight.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "sim/scenario/scenario_sitl.h"

namespace aperture::experiments {
namespace {

// Trajectory at 100 Hz whose error from the origin is error(t) along x.
std::vector<control::QuadState> TrajectoryWithError(double duration_s,
                                                    const std::function<double(double)>& error) {
  std::vector<control::QuadState> trajectory;
  for (int k = 0; k <= static_cast<int>(std::lround(duration_s * 100.0)); ++k) {
    control::QuadState s;
    s.t_s = 0.01 * k;
    s.p_WB.x() = error(s.t_s);
    trajectory.push_back(s);
  }
  return trajectory;
}

TEST(ComputeHoverMetricsTest, RecoveryTimeIsWhenTheErrorReturnsForGood) {
  // Push at 1 s: the error jumps to 0.3 m and decays linearly to 0 at 3 s, crossing 0.1 m at
  // 2.333 s; before the push a constant 0.02 m.
  const auto error = [](double t) {
    if (t < 1.0) return 0.02;
    return std::max(0.0, 0.3 * (3.0 - t) / 2.0);
  };
  const HoverMetrics m =
      ComputeHoverMetrics(TrajectoryWithError(6.0, error), Eigen::Vector3d::Zero(), {1.0}, 0.1, 1.0);
  ASSERT_EQ(m.pushes.size(), 1u);
  ASSERT_TRUE(m.pushes[0].recovery_time_s.has_value());
  // First sample within 0.1 m: t = 2.34 s (100 Hz grid) -> 1.34 s after the push.
  EXPECT_NEAR(*m.pushes[0].recovery_time_s, 1.34, 1e-9);
  EXPECT_NEAR(m.pushes[0].max_error_m, 0.3, 1e-9);
  EXPECT_NEAR(m.max_error_m, 0.3, 1e-9);
  // Outside [1, 2.34) s: 0.02 m before, the decaying tail (< 0.1 m) after.
  EXPECT_LT(m.max_error_outside_pushes_m, 0.1);
  EXPECT_GT(m.rms_error_m, m.rms_error_outside_pushes_m);
}

TEST(ComputeHoverMetricsTest, NoRecoveryWhenTheErrorNeverStaysInside) {
  // Leaves at the push and comes back only 0.5 s before the end (< recovery_hold_s).
  const auto error = [](double t) { return t >= 1.0 && t < 3.5 ? 0.5 : 0.0; };
  const HoverMetrics m =
      ComputeHoverMetrics(TrajectoryWithError(4.0, error), Eigen::Vector3d::Zero(), {1.0}, 0.1, 1.0);
  ASSERT_EQ(m.pushes.size(), 1u);
  EXPECT_FALSE(m.pushes[0].recovery_time_s.has_value());
  EXPECT_NEAR(m.max_error_outside_pushes_m, 0.0, 1e-12);  // the window runs to the end
  EXPECT_THROW(ComputeHoverMetrics({}, Eigen::Vector3d::Zero(), {}, 0.1, 1.0),
               std::invalid_argument);
  EXPECT_THROW(ComputeHoverMetrics(TrajectoryWithError(1.0, error), Eigen::Vector3d::Zero(), {},
                                   0.0, 1.0),
               std::invalid_argument);
}

TEST(LedHoverFlightTest, RejectsScenariosWithoutAnLedCamera) {
  const sim::Scenario gap = sim::BuildScenario(
      sim::LoadScenarioParams(sim::ScenarioConfig("gap", {}, {"cameras.front.width=64",
                                                              "cameras.front.height=48"})));
  sim::SitlRunnerParams params;
  sim::ConfigureSitlFromScenario(gap, &params);
  EXPECT_THROW(LedHoverFlight(gap, params), std::invalid_argument);
}

TEST(LedHoverFlightTest, HoldsTheSetpointFromLedPoseAndImuThroughAGustAndAPush) {
  // The default led scenario (752 x 480 ground camera, 40 Hz, 25 ms latency), 7 s with a 1.5 m/s
  // gust over [1, 2.5) s and the default 0.45 N s push moved to 3 s.
  sim::Scenario flown = sim::BuildScenario(sim::LoadScenarioParams(sim::ScenarioConfig(
      "led", {}, {"disturbances.gusts=[[1.0, 1.5, 1.5, 0.0, 0.0]]",
                  "disturbances.pushes=[[3.0, 0.45, 0.0, 0.0]]"})));
  sim::SitlRunnerParams params;
  params.duration_s = 7.0;
  params.SetSeed(7);
  sim::ConfigureSitlFromScenario(flown, &params);
  ASSERT_EQ(params.cameras.size(), 1u);
  EXPECT_DOUBLE_EQ(params.cameras[0].rate_hz, 40.0);
  EXPECT_DOUBLE_EQ(params.cameras[0].latency_s, 0.025);
  LedHoverFlight flight(flown, params);
  EXPECT_FALSE(flight.autopilot().UsesGroundTruth());  // LED pose + IMU only
  const sim::SitlResult sitl =
      sim::SitlRunner(params, &flown.scene()).Run(flight.autopilot(), sim::MakeScenarioHooks(&flown));
  ASSERT_EQ(sitl.outcome, sim::SitlResult::Outcome::kDurationReached) << sitl.reason;
  const LedHoverFlightResult result = flight.Finish(sitl, params.disturbances.pushes);

  // Every frame of the unoccluded 5-LED target yields a pose: 40 Hz.
  EXPECT_EQ(result.counts.frames, 280);
  EXPECT_EQ(result.counts.frames_with_pose, result.counts.frames);
  // Filter estimate vs ground truth: the LED poses are ~3-4 mm accurate at 2 m; 2 cm RMS allows
  // the transient after the push (the simulated impulse is invisible to the accelerometer).
  EXPECT_LT(result.estimate_rms_error_m, 0.02);
  // Hover (issue 6: 5 cm RMS): outside the push recovery, through the gust.
  EXPECT_LT(result.hover.rms_error_outside_pushes_m, 0.05);
  EXPECT_LT(result.hover.max_error_outside_pushes_m, 0.1);  // recovered = within 10 cm
  // The push (1 m/s) is recovered: back within 10 cm for 1 s, within 3 s.
  ASSERT_EQ(result.hover.pushes.size(), 1u);
  ASSERT_TRUE(result.hover.pushes[0].recovery_time_s.has_value());
  EXPECT_LT(*result.hover.pushes[0].recovery_time_s, 3.0);
  EXPECT_GT(result.hover.pushes[0].max_error_m, 0.1);  // the push did move it out
  EXPECT_LT(result.hover.pushes[0].max_error_m, 0.5);
}

}  // namespace
}  // namespace aperture::experiments
