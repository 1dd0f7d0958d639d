#include "servo/moment_servo.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "free_camera_simulation.h"

namespace aperture::servo {
namespace {

using testing::DownwardCameraMount;
using testing::ForwardCameraMount;
using testing::FreeCameraSimulation;
using testing::LevelPose;

constexpr double kMomentServoDt_s = 0.04;  // 25 Hz, the rate of ViSP's Bebop 2 servo example
constexpr int kSteps = 300;  // 12 s: the adaptive gain >= 0.7 /s leaves e^-8 of the error

// A free camera servoed from a displaced pose to the pose that saw the desired view.
struct MomentCase {
  std::string name;
  Eigen::Isometry3d T_BC;
  YawMode yaw;
  std::vector<Eigen::Vector3d> polygon_W;  // planar target
  Eigen::Isometry3d T_WB_goal;
  Eigen::Isometry3d T_WB_start;
  double goal_depth_m;  // target plane in front of the camera at the goal
};

// Irregular pentagon (no symmetry, second moments anisotropic: its orientation is defined).
std::vector<Eigen::Vector2d> Pentagon() {
  return {{0.5, 0.05}, {0.15, 0.3}, {-0.45, 0.15}, {-0.35, -0.15}, {0.25, -0.25}};
}

MomentCase DownwardCase() {
  MomentCase c{"downward_with_yaw", DownwardCameraMount(), YawMode::kOrientation, {}, {}, {}, 1.5};
  for (const Eigen::Vector2d& v : Pentagon()) c.polygon_W.emplace_back(v.x(), v.y(), 0.0);
  c.T_WB_goal = LevelPose({0.0, 0.0, 1.55}, 0.0);  // camera 1.5 m above the ground
  c.T_WB_start = LevelPose({0.4, -0.3, 2.2}, 35.0 * M_PI / 180.0);
  return c;
}

MomentCase ForwardCase() {
  // Opening in the wall x_W = 3 m, seen by the forward camera; yaw is held.
  MomentCase c{"forward_yaw_hold", ForwardCameraMount(), YawMode::kHold, {}, {}, {}, 2.5};
  for (const Eigen::Vector2d& v : Pentagon()) c.polygon_W.emplace_back(3.0, v.x(), 1.5 + v.y());
  c.T_WB_goal = LevelPose({0.4, 0.0, 1.5}, 0.0);
  c.T_WB_start = LevelPose({-0.6, 0.5, 1.1}, 0.0);
  return c;
}

class MomentServoConvergenceTest : public ::testing::TestWithParam<MomentCase> {};

TEST_P(MomentServoConvergenceTest, FeatureErrorDecreasesMonotonicallyToTheGoalPose) {
  const MomentCase& c = GetParam();
  MomentServoParams params;
  params.yaw = c.yaw;
  MomentServo servo(params, c.T_BC);
  const FreeCameraSimulation goal(c.T_WB_goal * c.T_BC, kMomentServoDt_s);
  servo.SetDesired(goal.Project(c.polygon_W), c.goal_depth_m);

  FreeCameraSimulation camera(c.T_WB_start * c.T_BC, kMomentServoDt_s);
  double previous_norm = std::numeric_limits<double>::infinity();
  double first_norm = 0.0;
  for (int k = 0; k < kSteps; ++k) {
    const ServoStepResult step = servo.Step(camera.Project(c.polygon_W));
    ASSERT_EQ(step.status, ServoStatus::kOk) << "step " << k;
    ASSERT_EQ(step.error.size(), c.yaw == YawMode::kOrientation ? 4 : 3);
    if (k == 0) first_norm = step.error_norm;
    // Strictly decreasing until the error reaches the level of rounding (1e-9).
    if (previous_norm > 1e-9) {
      EXPECT_LT(step.error_norm, previous_norm) << "step " << k;
    }
    previous_norm = step.error_norm;
    // The camera twist is the body reference's: no roll or pitch rate, the body stays level.
    const BodyVelocityReference back = BodyVelocityFromCameraTwist(step.twist_C, c.T_BC);
    EXPECT_LT((back.v_B - step.reference.v_B).norm(), 1e-12);
    EXPECT_NEAR(back.yaw_rate_radps, step.reference.yaw_rate_radps, 1e-12);
    if (c.yaw == YawMode::kHold) {
      EXPECT_EQ(step.reference.yaw_rate_radps, 0.0);
    }
    camera.Apply(step.twist_C);
  }
  EXPECT_GT(first_norm, 0.3);  // the start is far from the goal (20 cm..1 m, 35 deg)
  EXPECT_LT(previous_norm, 1e-3 * first_norm);
  // The features fix the pose: the camera ends at the goal (1 mm, 0.1 deg after e^-8 decay).
  const Eigen::Isometry3d T_WC_goal = c.T_WB_goal * c.T_BC;
  const Eigen::Isometry3d T_WC_end = camera.T_WC();
  EXPECT_LT((T_WC_end.translation() - T_WC_goal.translation()).norm(), 1e-3);
  EXPECT_LT(Eigen::AngleAxisd(T_WC_goal.linear().transpose() * T_WC_end.linear()).angle(),
            0.1 * M_PI / 180.0);
}

INSTANTIATE_TEST_SUITE_P(Mounts, MomentServoConvergenceTest,
                         ::testing::Values(DownwardCase(), ForwardCase()),
                         [](const auto& info) { return info.param.name; });

TEST(MomentServoTest, ErrorIsZeroAtTheGoalAndIndependentOfVertexOrder) {
  MomentServoParams params;
  params.yaw = YawMode::kOrientation;
  MomentServo servo(params, DownwardCameraMount());
  const MomentCase c = DownwardCase();
  const FreeCameraSimulation goal(c.T_WB_goal * c.T_BC, kMomentServoDt_s);
  std::vector<Eigen::Vector2d> view = goal.Project(c.polygon_W);
  servo.SetDesired(view, c.goal_depth_m);
  EXPECT_LT(servo.Step(view).error_norm, 1e-12);
  EXPECT_LT(servo.Step(view).reference.v_B.norm(), 1e-12);
  // The same contour listed the other way round and from another start vertex.
  std::vector<Eigen::Vector2d> reversed(view.rbegin(), view.rend());
  std::rotate(reversed.begin(), reversed.begin() + 2, reversed.end());
  EXPECT_LT(servo.Step(reversed).error_norm, 1e-12);
}

TEST(MomentServoTest, CentreAndAreaErrorsPointTheVelocityTheRightWay) {
  // Downward camera 1.5 m above the pentagon: the target appears shifted to image +x (= body -y
  // for this mount) and smaller than desired (too high): the body must move along -y_B and down.
  MomentServo servo(MomentServoParams{}, DownwardCameraMount());
  const MomentCase c = DownwardCase();
  servo.SetDesired(
      FreeCameraSimulation(c.T_WB_goal * c.T_BC, kMomentServoDt_s).Project(c.polygon_W), 1.5);
  const Eigen::Isometry3d T_WB = LevelPose({0.0, 0.3, 1.85}, 0.0);  // target to the right, far
  const ServoStepResult step =
      servo.Step(FreeCameraSimulation(T_WB * c.T_BC, kMomentServoDt_s).Project(c.polygon_W));
  EXPECT_GT(step.error[0], 0.0);  // x_n - x_n*: target right of where it should be
  EXPECT_GT(step.error[2], 0.0);  // a_n - a_n*: farther than desired
  EXPECT_LT(step.reference.v_B.y(), 0.0);
  EXPECT_LT(step.reference.v_B.z(), 0.0);
}

TEST(MomentServoTest, DegenerateViewGivesStatusAndZeroReference) {
  MomentServo servo(MomentServoParams{}, ForwardCameraMount());
  servo.SetDesired(Pentagon(), 2.0);
  const ServoStepResult step = servo.Step({{0.1, 0.1}, {0.2, 0.2}, {0.3, 0.3}});  // collinear
  EXPECT_EQ(step.status, ServoStatus::kDegenerateFeatures);
  EXPECT_EQ(step.reference.v_B, Eigen::Vector3d::Zero());
}

TEST(MomentServoTest, RejectsBadInput) {
  EXPECT_THROW(MomentServo(MomentServoParams{}, Eigen::Isometry3d(Eigen::Matrix4d::Constant(2.0))),
               std::invalid_argument);
  MomentServoParams orientation;
  orientation.yaw = YawMode::kOrientation;
  try {
    MomentServo servo(orientation, ForwardCameraMount());
    FAIL() << "a forward camera cannot servo yaw from the image orientation";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("yaw = hold"), std::string::npos) << e.what();
  }
  MomentServo downward(orientation, DownwardCameraMount());
  // A square's orientation is undefined (isotropic second moments).
  EXPECT_THROW(downward.SetDesired({{-0.1, -0.1}, {0.1, -0.1}, {0.1, 0.1}, {-0.1, 0.1}}, 1.0),
               std::invalid_argument);
  MomentServo servo(MomentServoParams{}, ForwardCameraMount());
  EXPECT_THROW(servo.Step(Pentagon()), std::invalid_argument);  // no desired view yet
  EXPECT_THROW(servo.SetDesired(Pentagon(), 0.0), std::invalid_argument);
  EXPECT_THROW(servo.SetDesired({{0.0, 0.0}, {0.1, 0.0}}, 1.0), std::invalid_argument);
  EXPECT_THROW(servo.SetDesired({{0.0, 0.0}, {0.1, NAN}, {0.0, 0.1}}, 1.0), std::invalid_argument);
  MomentServoParams bad;
  bad.min_area_n2 = -1.0;
  EXPECT_THROW(MomentServo(bad, ForwardCameraMount()), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::servo
