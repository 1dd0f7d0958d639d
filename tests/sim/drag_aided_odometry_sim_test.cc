// control::DragAidedOdometry on the simulator's IMU and range sensor (noise, default biases
// random walk, motor lag, rotor drag (F.2)) while a ground-truth autopilot flies a GapFlyt-like
// pattern: a diagonal scan, a 2 m dash forward, a stop. The estimate is compared with the true
// state at every IMU sample after the calibration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <random>

#include "control/drag_aided_odometry.h"
#include "sim/sitl/ground_truth_autopilot.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::control {
namespace {

// The odometry on a recorded flight's IMU and range readings, compared with the true state at
// every IMU sample after the calibration (in the odometry's frame: level, heading 0, origin below
// the start at the ground, so horizontal positions compare relative to the start).
struct OdometryErrors {
  double max_velocity_mps = 0.0, rms_velocity_xy_mps = 0.0, max_tilt_rad = 0.0;
  double max_height_m = 0.0, end_position_xy_m = 0.0, peak_speed_mps = 0.0;
  // RMS of the horizontal velocity estimate's change per sample: its white-noise derivative,
  // which a controller's velocity gain turns into tilt-command rate.
  double rms_velocity_step_mps = 0.0;
  int compared = 0;
  int coasting = 0;  // samples with the velocity coasting through suspected wind
};

OdometryErrors Replay(const sim::SitlResult& result, const Eigen::Vector3d& start_p_W,
                      DragAidedOdometry* odometry) {
  OdometryErrors errors;
  std::size_t range_index = 0, truth_index = 0;
  double squared_velocity_error = 0.0, squared_steps = 0.0;
  std::optional<Eigen::Vector2d> last_v_xy;
  for (const perception::ImuSample& sample : result.imu) {
    while (range_index < result.range.size() && result.range[range_index].t_s <= sample.t_s) {
      if (result.range[range_index].valid) odometry->AddRange(result.range[range_index].range_m);
      ++range_index;
    }
    odometry->AddImu(sample.t_s, sample.specific_force_B, sample.omega_B);
    if (!odometry->started()) continue;
    while (truth_index + 1 < result.trajectory.size() &&
           result.trajectory[truth_index + 1].t_s <= sample.t_s) {
      ++truth_index;
    }
    const QuadState& truth = result.trajectory[truth_index];
    const QuadState estimate = odometry->estimate();
    errors.max_velocity_mps = std::max(errors.max_velocity_mps, (estimate.v_W - truth.v_W).norm());
    const Eigen::Vector3d z_true = truth.q_WB * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d z_est = estimate.q_WB * Eigen::Vector3d::UnitZ();
    errors.max_tilt_rad = std::max(errors.max_tilt_rad, std::acos(std::min(1.0, z_true.dot(z_est))));
    errors.max_height_m =
        std::max(errors.max_height_m, std::abs(estimate.p_WB.z() - truth.p_WB.z()));
    errors.peak_speed_mps = std::max(errors.peak_speed_mps, truth.v_W.norm());
    squared_velocity_error += (estimate.v_W - truth.v_W).head<2>().squaredNorm();
    if (last_v_xy) squared_steps += (estimate.v_W.head<2>() - *last_v_xy).squaredNorm();
    last_v_xy = estimate.v_W.head<2>();
    errors.coasting += odometry->coasting() ? 1 : 0;
    ++errors.compared;
  }
  if (errors.compared > 0) {
    errors.rms_velocity_xy_mps = std::sqrt(squared_velocity_error / errors.compared);
    errors.rms_velocity_step_mps = std::sqrt(squared_steps / errors.compared);
  }
  const QuadState end = odometry->estimate();
  errors.end_position_xy_m =
      (end.p_WB.head<2>() - (result.trajectory.back().p_WB - start_p_W).head<2>()).norm();
  return errors;
}

// The GapFlyt-like pattern's simulation, with the IMU's noise densities and bias random walks
// times imu_noise_factor (`aperture bench faults`' imu_noise).
sim::SitlRunnerParams PatternParams(int seed, double imu_noise_factor) {
  sim::SitlRunnerParams params;
  params.duration_s = 9.0;
  params.initial_state.p_WB = Eigen::Vector3d(0.0, 0.0, 1.5);
  params.SetSeed(static_cast<std::uint64_t>(seed));
  params.imu.accel_bias_initial_B = Eigen::Vector3d(0.05, -0.04, 0.03);  // calibrated away
  params.imu.gyro_bias_initial_B = Eigen::Vector3d(0.004, -0.003, 0.002);
  params.imu.ScaleNoise(imu_noise_factor);
  return params;
}

sim::SitlResult FlyPattern(const sim::SitlRunnerParams& params) {
  sim::GroundTruthAutopilotParams autopilot_params;
  autopilot_params.waypoints = {{{0.0, 0.0, 1.5}, 0.0, 1.0},
                                {{0.0, 0.3, 1.8}, 0.0, 0.5},
                                {{2.0, 0.3, 1.8}, 0.0, 0.5},
                                {{2.0, 0.3, 1.8}, 0.0, 0.0}};
  // ~1 m/s and ~2 m/s^2 at most: the GapFlyt mission's manoeuvres (scan, servo, go through).
  autopilot_params.max_position_error_m = 0.8;
  sim::GroundTruthAutopilot autopilot(params.dynamics.vehicle, autopilot_params);
  return sim::SitlRunner(params, nullptr).Run(autopilot);
}

// The odometry (the vehicle's drag coefficients, defaults otherwise) with and without a feature,
// which `turn_off` switches off, on one flight.
struct Comparison {
  OdometryErrors with, without;
  double with_time_constant_s = 0.0, without_time_constant_s = 0.0;
};

Comparison Compare(const sim::SitlRunnerParams& params, const sim::SitlResult& result,
                   const std::function<void(DragAidedOdometryParams*)>& turn_off) {
  DragAidedOdometryParams on;
  on.rotor_drag_xy_per_s = params.dynamics.vehicle.rotor_drag_D_per_s.head<2>();
  DragAidedOdometryParams off = on;
  turn_off(&off);
  DragAidedOdometry with(on), without(off);
  Comparison comparison;
  comparison.with = Replay(result, params.initial_state.p_WB, &with);
  comparison.without = Replay(result, params.initial_state.p_WB, &without);
  comparison.with_time_constant_s = with.velocity_time_constant_s();
  comparison.without_time_constant_s = without.velocity_time_constant_s();
  return comparison;
}

class DragAidedOdometrySimTest : public ::testing::TestWithParam<int> {};

TEST_P(DragAidedOdometrySimTest, TracksTheTrueVelocityAttitudeAndHeight) {
  const sim::SitlRunnerParams params = PatternParams(GetParam(), 1.0);
  const sim::SitlResult result = FlyPattern(params);
  ASSERT_EQ(result.outcome, sim::SitlResult::Outcome::kDurationReached) << result.reason;

  DragAidedOdometryParams odometry_params;
  odometry_params.rotor_drag_xy_per_s = params.dynamics.vehicle.rotor_drag_D_per_s.head<2>();
  DragAidedOdometry odometry(odometry_params);
  const OdometryErrors errors = Replay(result, params.initial_state.p_WB, &odometry);
  ASSERT_GT(errors.compared, 3000);      // 500 Hz over > 6 s
  ASSERT_GT(errors.peak_speed_mps, 0.8);  // the dash exercised the drag measurement
  // The calibration at "rest": the flight controller's rate loop runs on the biased gyro, so the
  // vehicle turns at -b_gyro and drifts by a few cm/s while the odometry averages f_B, which
  // biases the x_B, y_B accelerometer calibration by d v ~ 0.01 m/s^2 (the noise alone: 0.006).
  EXPECT_NEAR(odometry.accel_bias_xy_B().x(), 0.05, 0.015);
  EXPECT_NEAR(odometry.accel_bias_xy_B().y(), -0.04, 0.015);
  EXPECT_NEAR(odometry.gyro_bias_B().x(), 0.004, 1e-3);
  // The default IMU's noise keeps the wind gate at its floor.
  EXPECT_DOUBLE_EQ(odometry.wind_gate_mps(), odometry_params.wind_gate_mps);
  // ... and the velocity time constant at its configured value.
  EXPECT_DOUBLE_EQ(odometry.velocity_time_constant_s(), odometry_params.velocity_time_constant_s);
  // Horizontal velocity: that calibration error divided by d_y = 0.35 is a ~3-4 cm/s offset; the
  // drag measurement also lags the thrust tilt by the motor lag in the dash's accelerations. RMS 6
  // cm/s and 0.3 m/s at worst fail a wrong drag sign or coefficient (errors of the order of the
  // speed).
  EXPECT_LT(errors.rms_velocity_xy_mps, 0.06);
  EXPECT_LT(errors.max_velocity_mps, 0.3);
  // Attitude: 2 deg; the accelerometer update is gated out in the accelerations.
  EXPECT_LT(errors.max_tilt_rad, 2.0 * M_PI / 180.0);
  // Height from the 2 cm range sensor: 5 cm.
  EXPECT_LT(errors.max_height_m, 0.05);
  // Position drift: the velocity offset integrated over the 8.5 s after the calibration, 0.35 m
  // (the mission needs ~1 m of it between the scan and the stop beyond the wall).
  EXPECT_LT(errors.end_position_xy_m, 0.35);
}

// A 2.5 m/s gust for 1 s (`aperture bench faults`' default gust) while a ground-truth autopilot
// holds a hover: the drag measurement reads the airspeed, 2.5 m/s off the true velocity at once.
// The wind gate coasts through it on the integrated acceleration; without the gate the estimate
// follows the air (the GapFlyt mission then flew into the wall with the gust).
TEST(DragAidedOdometryWindTest, CoastsThroughAGustInsteadOfFollowingTheAir) {
  sim::SitlRunnerParams params;
  params.duration_s = 6.0;
  params.initial_state.p_WB = Eigen::Vector3d(0.0, 0.0, 1.5);
  params.SetSeed(3);
  params.disturbances.gusts.push_back({2.0, 1.0, Eigen::Vector3d(1.5, -2.0, 0.0)});
  sim::GroundTruthAutopilotParams autopilot_params;
  autopilot_params.waypoints = {{{0.0, 0.0, 1.5}, 0.0, 0.0}};
  sim::GroundTruthAutopilot autopilot(params.dynamics.vehicle, autopilot_params);
  const sim::SitlResult result = sim::SitlRunner(params, nullptr).Run(autopilot);
  ASSERT_EQ(result.outcome, sim::SitlResult::Outcome::kDurationReached) << result.reason;

  const Comparison gate = Compare(params, result, [](DragAidedOdometryParams* p) {
    p->wind_gate_mps = 1e9;
  });
  const OdometryErrors& on = gate.with;
  const OdometryErrors& off = gate.without;
  // Coasting for about the gust (1 s = 500 samples, plus the residual's settling at both ends).
  EXPECT_GT(on.coasting, 400);
  EXPECT_LT(on.coasting, 700);
  EXPECT_EQ(off.coasting, 0);
  EXPECT_GT(off.max_velocity_mps, 1.5);  // follows the 2.5 m/s air
  EXPECT_LT(on.max_velocity_mps, 0.3);
  // Position: 0.18 m here (the ~20 ms before the low-passed residual crosses the gate at both of
  // the gust's ends, and the prediction's drift while coasting) against 2.5 m without the gate.
  EXPECT_LT(on.end_position_xy_m, 0.3);
  EXPECT_GT(off.end_position_xy_m, 0.8);
}

// x10 the default IMU noise (`aperture bench faults`' top imu_noise level): at the fixed 0.3 s
// time constant the drag correction passes the accelerometer's noise / d / tau into the velocity's
// derivative (a GapFlyt hover on it jittered at ~0.6 rad/s of roll/pitch rate); the calibration
// lengthens tau to q_v / max_correction_noise, which smooths that derivative ~8x (0.018 ->
// 0.0022 m/s per sample here) and also lowers the velocity error (RMS 0.20-0.28 -> 0.14-0.20
// m/s: the bias error's b (tau - 1 / d) shrinks, drag_aided_odometry.h).
TEST_P(DragAidedOdometrySimTest, ANoisierAccelerometerLengthensTheVelocityTimeConstant) {
  const sim::SitlRunnerParams params = PatternParams(GetParam(), 10.0);
  const sim::SitlResult result = FlyPattern(params);
  ASSERT_EQ(result.outcome, sim::SitlResult::Outcome::kDurationReached) << result.reason;
  const Comparison tau = Compare(params, result, [](DragAidedOdometryParams* p) {
    p->max_correction_noise = 1e9;
  });
  const OdometryErrors& lengthened = tau.with;
  const OdometryErrors& kept = tau.without;
  // q_v = 10 x 3.9e-3 / d_y: tau = 0.111 / 0.075 ~ 1.5 s (the at-rest spread is measured in
  // hover, a little above the sensor's own).
  const DragAidedOdometryParams defaults;
  const double expected_s = 10.0 * 3.9e-3 / params.dynamics.vehicle.rotor_drag_D_per_s.y() /
                            defaults.max_correction_noise;
  EXPECT_NEAR(tau.with_time_constant_s, expected_s, 0.15 * expected_s);
  EXPECT_DOUBLE_EQ(tau.without_time_constant_s, defaults.velocity_time_constant_s);
  EXPECT_LT(lengthened.rms_velocity_step_mps, 0.25 * kept.rms_velocity_step_mps);
  EXPECT_LT(lengthened.rms_velocity_xy_mps, kept.rms_velocity_xy_mps);
  EXPECT_LT(lengthened.max_velocity_mps, 0.45);
}

INSTANTIATE_TEST_SUITE_P(Seeds, DragAidedOdometrySimTest, ::testing::Values(1, 2));

// The gate follows the accelerometer's noise measured at rest: sigma / d through the residual's
// low-pass, times wind_gate_sigmas, once that exceeds the floor.
TEST(DragAidedOdometryWindTest, TheGateRisesWithTheAccelerometersNoise) {
  DragAidedOdometryParams params;
  params.rotor_drag_xy_per_s = Eigen::Vector2d(0.5, 0.35);
  DragAidedOdometry odometry(params);
  std::mt19937_64 rng(7);
  const double sigma_mps2 = 0.6;  // per sample: ~x10 the simulator's default IMU at 500 Hz
  std::normal_distribution<double> noise(0.0, sigma_mps2);
  const double dt_s = 0.002;
  for (int i = 0; odometry.wind_gate_mps() == 0.0 && i < 1000; ++i) {
    odometry.AddImu(i * dt_s, Eigen::Vector3d(noise(rng), noise(rng), 9.81),
                    Eigen::Vector3d::Zero());
  }
  // y has the smaller drag coefficient: the larger velocity noise.
  const double expected = params.wind_gate_sigmas * sigma_mps2 / 0.35 *
                          std::sqrt(dt_s / (2.0 * params.wind_residual_time_constant_s));
  ASSERT_GT(expected, params.wind_gate_mps);
  EXPECT_NEAR(odometry.wind_gate_mps(), expected, 0.1 * expected);
}

// The velocity time constant from the noise measured at rest: tau = sigma sqrt(dt) / d_y /
// max_correction_noise once that exceeds the configured 0.3 s.
TEST(DragAidedOdometryNoiseTest, TheTimeConstantFollowsTheMeasuredNoise) {
  DragAidedOdometryParams params;
  params.rotor_drag_xy_per_s = Eigen::Vector2d(0.5, 0.35);
  const double dt_s = 0.002;
  for (const double sigma_mps2 : {0.05, 0.6}) {  // per sample: below and ~x7 the default IMU's
    DragAidedOdometry odometry(params);
    std::mt19937_64 rng(11);
    std::normal_distribution<double> noise(0.0, sigma_mps2);
    for (int i = 0; odometry.velocity_time_constant_s() == 0.0 && i < 1000; ++i) {
      odometry.AddImu(i * dt_s, Eigen::Vector3d(noise(rng), noise(rng), 9.81),
                      Eigen::Vector3d::Zero());
    }
    const double expected = std::max(params.velocity_time_constant_s,
                                     sigma_mps2 * std::sqrt(dt_s) / 0.35 /
                                         params.max_correction_noise);
    EXPECT_NEAR(odometry.velocity_time_constant_s(), expected, 0.1 * expected) << sigma_mps2;
  }
}

TEST(DragAidedOdometryTest, RejectsBadInput) {
  DragAidedOdometryParams params;
  params.rotor_drag_xy_per_s.y() = 0.0;  // no drag: no velocity measurement
  EXPECT_THROW(DragAidedOdometry{params}, std::invalid_argument);
  params = DragAidedOdometryParams{};
  params.max_correction_noise = 0.0;
  EXPECT_THROW(DragAidedOdometry{params}, std::invalid_argument);
  DragAidedOdometry odometry{DragAidedOdometryParams{}};
  odometry.AddImu(0.0, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d::Zero());
  EXPECT_THROW(odometry.AddImu(0.0, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d::Zero()),
               std::invalid_argument);  // not after the previous sample
  EXPECT_THROW(odometry.AddImu(0.1, Eigen::Vector3d(NAN, 0, 9.81), Eigen::Vector3d::Zero()),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
