#include "planning/pose_hold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "control/constants.h"

namespace aperture::planning {
namespace {

using control::kGravity_mps2;

// IMU at rest, level: the accelerometer reads +g along z_B.
perception::ImuSample RestingImu(double t_s) {
  perception::ImuSample sample;
  sample.t_s = t_s;
  sample.specific_force_B = Eigen::Vector3d(0.0, 0.0, kGravity_mps2);
  return sample;
}

// A pose of the sensor frame X mounted at p_BX (no rotation) on a level body at p_WB.
perception::PoseMeasurement PoseOfBodyAt(double t_s, const Eigen::Vector3d& p_WB,
                                         const Eigen::Vector3d& p_BX) {
  perception::PoseMeasurement z;
  z.t_s = t_s;
  z.p_WX = p_WB + p_BX;
  z.p_BX = p_BX;
  z.covariance = perception::Matrix6d::Identity() * 1e-6;  // 1 mm, 1 mrad
  return z;
}

class PoseHoldTest : public ::testing::Test {
 protected:
  control::VehicleParameters vehicle_;
  PoseHoldParams params_;
  PoseHoldSetpoint setpoint_{Eigen::Vector3d(0.0, 0.0, 2.0), 0.0};
};

TEST_F(PoseHoldTest, CommandsNothingUntilTheFirstPose) {
  PoseHold hold(vehicle_, params_, setpoint_);
  for (int k = 1; k <= 10; ++k) hold.AddImu(RestingImu(0.002 * k));
  EXPECT_FALSE(hold.initialized());
  EXPECT_FALSE(hold.estimate().has_value());
  EXPECT_EQ(hold.Step(0.02).kind, perception::AutopilotCommand::Kind::kNone);
  EXPECT_EQ(hold.status(0.02), "waiting for pose");
}

TEST_F(PoseHoldTest, FirstPoseStartsTheFilterAtTheBodyPoseAndReplaysTheImu) {
  PoseHold hold(vehicle_, params_, setpoint_);
  for (int k = 1; k <= 50; ++k) hold.AddImu(RestingImu(0.002 * k));  // up to 0.1 s
  // A pose measured 30 ms ago (latency) of a frame 10 cm below the body.
  const Eigen::Vector3d p_BX(0.0, 0.0, -0.1);
  const std::vector<perception::PoseFusionOutcome> outcomes =
      hold.AddPose(PoseOfBodyAt(0.07, setpoint_.p_W, p_BX));
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_TRUE(outcomes[0].started_filter);
  ASSERT_TRUE(hold.initialized());
  const perception::PoseImuEstimate estimate = *hold.estimate();
  // Replayed to the latest IMU sample; at rest with the true gravity it stays put (the IMU is
  // exact, so only rounding moves it).
  EXPECT_NEAR(estimate.state.t_s, 0.1, 1e-12);
  EXPECT_LT((estimate.state.p_WB - setpoint_.p_W).norm(), 1e-9);
  EXPECT_LT(estimate.state.v_W.norm(), 1e-9);
  // At the set-point, at rest: hover thrust, no rates (no drag terms at zero velocity).
  const perception::AutopilotCommand command = hold.Step(0.1);
  ASSERT_EQ(command.kind, perception::AutopilotCommand::Kind::kThrustRates);
  EXPECT_NEAR(command.thrust_rates.collective_thrust_mps2, kGravity_mps2, 1e-6);
  EXPECT_LT(command.thrust_rates.omega_des_B.norm(), 1e-6);
  EXPECT_EQ(hold.status(0.1), "hold");
}

TEST_F(PoseHoldTest, PullsTowardsTheSetpointAndIntegratesAPersistentError) {
  params_.disturbance_time_constant_s = 0.0;  // isolate the integral action
  PoseHold hold(vehicle_, params_, setpoint_);
  hold.AddImu(RestingImu(0.002));
  // The body held 10 cm short of the set-point in x (e.g. by a steady force the test does not
  // model): the command tilts towards +x, and the integral grows by k_i * e * t.
  const Eigen::Vector3d p_WB(-0.1, 0.0, 2.0);
  hold.AddPose(PoseOfBodyAt(0.002, p_WB, Eigen::Vector3d::Zero()));
  perception::AutopilotCommand command;
  for (int k = 0; k <= 100; ++k) {
    const double t_s = 0.002 + 0.01 * k;
    if (k > 0) {
      for (int i = 1; i <= 5; ++i) hold.AddImu(RestingImu(t_s - 0.01 + 0.002 * i));
      hold.AddPose(PoseOfBodyAt(t_s, p_WB, Eigen::Vector3d::Zero()));
    }
    command = hold.Step(t_s);
  }
  // Pitching forward (towards +x) is a positive rate about y_B.
  EXPECT_GT(command.thrust_rates.omega_des_B.y(), 0.0);
  // 1 s at 0.1 m error, integrated clamped to max_integrated_error_m (anti-windup):
  // feed-forward k_i * 0.05 m * 1 s = 0.15 m/s^2 along +x (the filter holds the pose to < 1 mm,
  // so the error stays above the clamp).
  ASSERT_LT(params_.max_integrated_error_m, 0.1);
  EXPECT_NEAR(hold.integral_accel_W().x(),
              params_.integral_gain_per_s3 * params_.max_integrated_error_m * 1.0, 1e-6);
  EXPECT_NEAR(hold.integral_accel_W().y(), 0.0, 1e-6);
}

TEST_F(PoseHoldTest, DisturbanceObserverMeasuresAnExternalForceFromTheAccelerometer) {
  PoseHold hold(vehicle_, params_, setpoint_);
  hold.AddImu(RestingImu(0.002));
  hold.AddPose(PoseOfBodyAt(0.002, setpoint_.p_W, Eigen::Vector3d::Zero()));
  hold.Step(0.002);  // first command: hover thrust, c_prev = g
  // From now on the accelerometer reads an extra 0.5 m/s^2 along x_B (wind drag) while the
  // vehicle is held in place. After 10 time constants the estimate has converged to it.
  const double t_end = 0.002 + 10.0 * params_.disturbance_time_constant_s;
  double t_s = 0.002;
  while (t_s < t_end) {
    t_s += 0.01;
    for (int i = 1; i <= 5; ++i) {
      perception::ImuSample sample = RestingImu(t_s - 0.01 + 0.002 * i);
      sample.specific_force_B.x() += 0.5;
      hold.AddImu(sample);
    }
    hold.Step(t_s);
  }
  // The filter attributes part of the specific force to velocity/bias between poses (none arrive
  // here), and c_prev follows the command; 5 % of the disturbance covers both.
  EXPECT_NEAR(hold.disturbance_accel_W().x(), 0.5, 0.025);
  EXPECT_NEAR(hold.disturbance_accel_W().y(), 0.0, 0.025);
}

TEST_F(PoseHoldTest, DisturbanceObserverSeesTheMeanSpecificForceOfAStep) {
  // Five IMU samples per control step of a vibration that sums to zero over each step but ends
  // every step at +1 m/s^2 along x_B: sampling the last one would read a steady 1 m/s^2 push
  // (the aliasing that made a noisy IMU shake the whole loop); the step's mean reads none.
  PoseHold hold(vehicle_, params_, setpoint_);
  hold.AddImu(RestingImu(0.002));
  hold.AddPose(PoseOfBodyAt(0.002, setpoint_.p_W, Eigen::Vector3d::Zero()));
  hold.Step(0.002);
  const double vibration_mps2[5] = {0.0, 1.0, -1.0, -1.0, 1.0};
  double t_s = 0.002;
  while (t_s < 0.002 + 10.0 * params_.disturbance_time_constant_s) {
    t_s += 0.01;
    for (int i = 1; i <= 5; ++i) {
      perception::ImuSample sample = RestingImu(t_s - 0.01 + 0.002 * i);
      sample.specific_force_B.x() += vibration_mps2[i - 1];
      hold.AddImu(sample);
    }
    hold.Step(t_s);
  }
  EXPECT_NEAR(hold.disturbance_accel_W().x(), 0.0, 0.025);
}

TEST_F(PoseHoldTest, RejectsBadParameters) {
  // One invalid field at a time.
  const std::vector<std::function<void(PoseHoldParams*)>> breakers = {
      [](PoseHoldParams* p) { p->max_position_error_m = 0.0; },
      [](PoseHoldParams* p) { p->max_integrated_error_m = -0.01; },
      [](PoseHoldParams* p) { p->max_consecutive_rejections = 0; },
      [](PoseHoldParams* p) { p->disturbance_time_constant_s = -0.1; },
      [](PoseHoldParams* p) { p->max_pose_age_s = std::nan(""); },
      [](PoseHoldParams* p) { p->filter.mahalanobis_gate = -1.0; },
      [](PoseHoldParams* p) { p->max_process_noise_scale = 0.5; },
      [](PoseHoldParams* p) { p->max_process_noise_scale = INFINITY; },
  };
  for (std::size_t i = 0; i < breakers.size(); ++i) {
    PoseHoldParams params = params_;
    breakers[i](&params);
    EXPECT_THROW(PoseHold(vehicle_, params, setpoint_), std::invalid_argument) << "breaker " << i;
  }
  PoseHoldSetpoint bad = setpoint_;
  bad.heading_rad = INFINITY;
  EXPECT_THROW(PoseHold(vehicle_, params_, bad), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
