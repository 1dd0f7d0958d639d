#include "servo/pid_servo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "free_camera_simulation.h"

namespace aperture::servo {
namespace {

PidServoParams HandParams() {
  PidServoParams params;
  params.kp_mps = 2.0;
  params.ki_mps2 = 0.5;
  params.kd_m = 0.1;
  params.forward_pitch_deg = 3.0;
  return params;
}

TEST(PidServoTest, SignsAndTermsMatchTheHandComputedCase) {
  // Forward camera, body axis through the principal point. Safe point right of and above the
  // centre: fly right (-y_B) and up (+z_B), forward at g tan(3 deg) / d_x.
  PidServo pid(HandParams(), testing::ForwardCameraMount(), 0.5);
  const double forward = 9.81 * std::tan(3.0 * M_PI / 180.0) / 0.5;  // 1.0283 m/s
  EXPECT_NEAR(pid.forward_speed_mps(), forward, 1e-12);
  EXPECT_LT(pid.body_axis_n().norm(), 1e-15);

  ServoStepResult step = pid.Step(0.0, Eigen::Vector2d(0.1, -0.05));
  // First step: proportional only (no derivative, no integral yet): 2 * (0.1, -0.05).
  EXPECT_NEAR(step.error[0], 0.1, 1e-15);
  EXPECT_NEAR(step.error[1], -0.05, 1e-15);
  EXPECT_NEAR(step.reference.v_B.x(), forward, 1e-12);
  EXPECT_NEAR(step.reference.v_B.y(), -0.2, 1e-12);
  EXPECT_NEAR(step.reference.v_B.z(), 0.1, 1e-12);
  EXPECT_EQ(step.reference.yaw_rate_radps, 0.0);

  // 0.1 s later, e = (0.12, -0.05): P (0.24, -0.1) + I 0.5 * 0.1 e = (0.006, -0.0025)
  // + D 0.1 * (0.2, 0) = (0.02, 0)  ->  (0.266, -0.1025) along image x, y.
  step = pid.Step(0.1, Eigen::Vector2d(0.12, -0.05));
  EXPECT_NEAR(step.reference.v_B.y(), -0.266, 1e-12);
  EXPECT_NEAR(step.reference.v_B.z(), 0.1025, 1e-12);

  // The camera twist is the body reference's.
  const BodyVelocityReference back =
      BodyVelocityFromCameraTwist(step.twist_C, testing::ForwardCameraMount());
  EXPECT_LT((back.v_B - step.reference.v_B).norm(), 1e-12);

  // A large error saturates at max_speed_mps (1 m/s) per image axis.
  step = pid.Step(0.2, Eigen::Vector2d(-2.0, 2.0));
  EXPECT_NEAR(step.reference.v_B.y(), 1.0, 1e-12);   // left: safe point far left
  EXPECT_NEAR(step.reference.v_B.z(), -1.0, 1e-12);  // down: safe point far below

  // Reset forgets the history: the first step after it is proportional again.
  pid.Reset();
  step = pid.Step(0.0, Eigen::Vector2d(0.1, -0.05));
  EXPECT_NEAR(step.reference.v_B.y(), -0.2, 1e-12);
}

TEST(PidServoTest, PitchedCameraAlignsTheBodyAxisNotTheOpticalAxis) {
  // Camera pitched 10 deg down: the flight direction x_B appears tan(10 deg) above the centre.
  // A safe point at the image centre lies below the flight direction: descend, no lateral motion.
  Eigen::Isometry3d T_BC = testing::ForwardCameraMount();
  T_BC.linear() =
      Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix() *
      T_BC.linear();
  PidServo pid(HandParams(), T_BC, 0.5);
  EXPECT_NEAR(pid.body_axis_n().x(), 0.0, 1e-15);
  EXPECT_NEAR(pid.body_axis_n().y(), -std::tan(10.0 * M_PI / 180.0), 1e-15);
  const ServoStepResult step = pid.Step(0.0, Eigen::Vector2d::Zero());
  EXPECT_NEAR(step.reference.v_B.y(), 0.0, 1e-15);
  EXPECT_NEAR(step.reference.v_B.z(), -2.0 * std::tan(10.0 * M_PI / 180.0), 1e-12);
}

TEST(PidServoTest, RejectsBadInput) {
  EXPECT_THROW(PidServo(HandParams(), testing::ForwardCameraMount(), 0.0), std::invalid_argument);
  EXPECT_THROW(PidServo(HandParams(), testing::DownwardCameraMount(), 0.5),
               std::invalid_argument);  // x_B has no image
  PidServoParams bad = HandParams();
  bad.forward_pitch_deg = 45.0;
  EXPECT_THROW(PidServo(bad, testing::ForwardCameraMount(), 0.5), std::invalid_argument);
  bad = HandParams();
  bad.kd_m = -1.0;
  EXPECT_THROW(bad.Validate(), std::invalid_argument);
  PidServo pid(HandParams(), testing::ForwardCameraMount(), 0.5);
  pid.Step(1.0, Eigen::Vector2d::Zero());
  EXPECT_THROW(pid.Step(1.0, Eigen::Vector2d::Zero()), std::invalid_argument);  // time repeats
  EXPECT_THROW(pid.Step(2.0, Eigen::Vector2d(NAN, 0.0)), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::servo
