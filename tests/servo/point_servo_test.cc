#include "servo/point_servo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "free_camera_simulation.h"

namespace aperture::servo {
namespace {

using testing::DownwardCameraMount;
using testing::FreeCameraSimulation;
using testing::LevelPose;

constexpr double kDt_s = 0.04;

// Corners of a 0.3 m tag on the ground, centred at `centre_W`.
std::vector<Eigen::Vector3d> TagCorners(const Eigen::Vector3d& centre_W) {
  const double h = 0.15;
  return {centre_W + Eigen::Vector3d(-h, -h, 0), centre_W + Eigen::Vector3d(h, -h, 0),
          centre_W + Eigen::Vector3d(h, h, 0), centre_W + Eigen::Vector3d(-h, h, 0)};
}

PointServo::Corners ToCorners(const std::vector<Eigen::Vector2d>& image) {
  return {image[0], image[1], image[2], image[3]};
}

// Issue 16's tag servo: a downward camera brought over a tag from a displaced, turned pose.
TEST(PointServoTest, FeatureErrorDecreasesMonotonicallyToTheGoalPose) {
  const Eigen::Isometry3d T_BC = DownwardCameraMount();
  const std::vector<Eigen::Vector3d> tag_W = TagCorners(Eigen::Vector3d::Zero());
  const Eigen::Isometry3d T_WB_goal = LevelPose({0.0, 0.0, 2.05}, 0.0);  // camera 2 m up
  PointServo servo(PointServoParams{}, T_BC);
  servo.SetDesired(ToCorners(FreeCameraSimulation(T_WB_goal * T_BC, kDt_s).Project(tag_W)), 2.0);

  FreeCameraSimulation camera(LevelPose({0.5, -0.4, 2.6}, 40.0 * M_PI / 180.0) * T_BC, kDt_s);
  double previous_norm = std::numeric_limits<double>::infinity();
  double first_norm = 0.0;
  for (int k = 0; k < 300; ++k) {
    const double depth_m = camera.T_WC().translation().z();  // a range sensor's reading
    const ServoStepResult step = servo.Step(ToCorners(camera.Project(tag_W)), depth_m);
    ASSERT_EQ(step.error.size(), 8);
    if (k == 0) first_norm = step.error_norm;
    if (previous_norm > 1e-9) {
      EXPECT_LT(step.error_norm, previous_norm) << "step " << k;
    }
    previous_norm = step.error_norm;
    camera.Apply(step.twist_C);
  }
  EXPECT_GT(first_norm, 0.3);
  EXPECT_LT(previous_norm, 1e-3 * first_norm);
  const Eigen::Isometry3d T_WC_goal = T_WB_goal * T_BC;
  EXPECT_LT((camera.T_WC().translation() - T_WC_goal.translation()).norm(), 1e-3);
  EXPECT_LT(Eigen::AngleAxisd(T_WC_goal.linear().transpose() * camera.T_WC().linear()).angle(),
            0.1 * M_PI / 180.0);
}

TEST(PointServoTest, YawErrorTurnsTheBodyBack) {
  // Body turned +20 deg about z: the tag appears turned the other way; the law turns back.
  const Eigen::Isometry3d T_BC = DownwardCameraMount();
  const std::vector<Eigen::Vector3d> tag_W = TagCorners(Eigen::Vector3d::Zero());
  PointServo servo(PointServoParams{}, T_BC);
  servo.SetDesired(
      ToCorners(FreeCameraSimulation(LevelPose({0, 0, 2.05}, 0.0) * T_BC, kDt_s).Project(tag_W)),
      2.0);
  const ServoStepResult step = servo.Step(
      ToCorners(FreeCameraSimulation(LevelPose({0, 0, 2.05}, 20.0 * M_PI / 180.0) * T_BC, kDt_s)
                    .Project(tag_W)),
      2.0);
  EXPECT_LT(step.reference.yaw_rate_radps, 0.0);
  EXPECT_LT(step.reference.v_B.norm(), 1e-9);  // pure rotation about the tag centre's vertical
}

TEST(PointServoTest, RejectsBadInput) {
  PointServo servo(PointServoParams{}, DownwardCameraMount());
  const PointServo::Corners square = {Eigen::Vector2d(-0.1, -0.1), Eigen::Vector2d(0.1, -0.1),
                                      Eigen::Vector2d(0.1, 0.1), Eigen::Vector2d(-0.1, 0.1)};
  EXPECT_THROW(servo.Step(square, 1.0), std::invalid_argument);  // no desired view yet
  EXPECT_THROW(servo.SetDesired(square, -1.0), std::invalid_argument);
  PointServo::Corners doubled = square;
  doubled[3] = doubled[0];
  EXPECT_THROW(servo.SetDesired(doubled, 1.0), std::invalid_argument);
  servo.SetDesired(square, 1.0);
  PointServo::Corners nan = square;
  nan[1].x() = NAN;
  EXPECT_THROW(servo.Step(nan, 1.0), std::invalid_argument);
  EXPECT_THROW(servo.Step(square, 0.0), std::invalid_argument);
  PointServoParams bad;
  bad.gain.at_zero_per_s = 0.0;
  EXPECT_THROW(PointServo(bad, DownwardCameraMount()), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::servo
