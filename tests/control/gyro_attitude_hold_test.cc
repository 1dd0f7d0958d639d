#include "control/gyro_attitude_hold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace aperture::control {
namespace {

TEST(GyroAttitudeHoldTest, IntegratesTheGyroFromTheFirstSample) {
  GyroAttitudeHold hold(AttitudeControllerGains{});
  // 0.2 rad/s about x for 0.5 s at 500 Hz: the first sample only starts, then 250 steps.
  const Eigen::Vector3d omega_B(0.2, 0.0, 0.0);
  for (int k = 0; k <= 250; ++k) hold.AddImu(1.0 + 0.002 * k, omega_B);
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
  EXPECT_LT(hold.q_B0B().angularDistance(expected), 1e-9);
}

TEST(GyroAttitudeHoldTest, CommandsTheRatesBackToTheStartAttitude) {
  GyroAttitudeHold hold(AttitudeControllerGains{});
  EXPECT_TRUE(hold.Command(9.81).omega_des_B.isZero());  // level: nothing to correct
  hold.AddImu(0.0, Eigen::Vector3d(0.0, 0.0, 0.0));
  hold.AddImu(0.1, Eigen::Vector3d(0.0, 1.0, 0.0));  // pitched by 0.05 rad (trapezoid)
  const ThrustRatesCommand command = hold.Command(9.81);
  EXPECT_DOUBLE_EQ(command.collective_thrust_mps2, 9.81);
  // Back about -y, proportional to the tilt (p_rp of Table A.2), nothing about x.
  EXPECT_NEAR(command.omega_des_B.y(), -AttitudeControllerGains{}.p_rp_per_s * 0.05, 0.02);
  EXPECT_NEAR(command.omega_des_B.x(), 0.0, 1e-9);
}

TEST(GyroAttitudeHoldTest, RejectsBadSamples) {
  GyroAttitudeHold hold(AttitudeControllerGains{});
  EXPECT_THROW(hold.AddImu(NAN, Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(hold.AddImu(0.0, Eigen::Vector3d(INFINITY, 0.0, 0.0)), std::invalid_argument);
  hold.AddImu(1.0, Eigen::Vector3d::Zero());
  EXPECT_THROW(hold.AddImu(0.5, Eigen::Vector3d::Zero()), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
