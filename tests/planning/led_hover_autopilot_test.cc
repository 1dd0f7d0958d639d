#include "planning/led_hover_autopilot.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "control/so3.h"
#include "perception/camera/pinhole_camera.h"

namespace aperture::planning {
namespace {

using control::Vector6d;
using perception::Matrix6d;
using ::testing::HasSubstr;

Eigen::Isometry3d RandomPose(std::mt19937_64* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Vector6d xi;
  for (int i = 0; i < 6; ++i) xi(i) = normal(*rng);
  return control::ExpSe3(xi);
}

Eigen::Vector3d LogRotation(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

TEST(BodyPoseFromLedPoseTest, GroundCameraLookingUpAtTheTarget) {
  // The led scenario's geometry: camera 5 cm above the ground looking up (R_WC = I), the target
  // 1.95 m above it, LEDs in B (T_BT = I): the body is at 2 m.
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  T_WC.translation() = Eigen::Vector3d(0.0, 0.0, 0.05);
  Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
  T_CT.translation() = Eigen::Vector3d(0.1, -0.2, 1.95);
  const Eigen::Isometry3d T_WB = BodyPoseFromLedPose(T_WC, T_CT, Eigen::Isometry3d::Identity());
  EXPECT_TRUE(T_WB.translation().isApprox(Eigen::Vector3d(0.1, -0.2, 2.0), 1e-12));
  EXPECT_TRUE(T_WB.linear().isIdentity(1e-12));
}

TEST(BodyPoseFromLedPoseTest, EveryLedLandsWhereTheCameraSeesIt) {
  // p_W of an LED through the body (T_WB T_BT p_T) equals the camera's view (T_WC T_CT p_T), and
  // the body origin is T_WC T_CT T_BT^-1 applied to 0: checks the composition order and inverse.
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Isometry3d T_WC = RandomPose(&rng);
    const Eigen::Isometry3d T_CT = RandomPose(&rng);
    const Eigen::Isometry3d T_BT = RandomPose(&rng);
    const Eigen::Isometry3d T_WB = BodyPoseFromLedPose(T_WC, T_CT, T_BT);
    const Eigen::Vector3d p_T(0.1, -0.05, 0.02);
    EXPECT_TRUE((T_WB * (T_BT * p_T)).isApprox(T_WC * (T_CT * p_T), 1e-9));
    EXPECT_NEAR((T_WB.linear().transpose() * T_WB.linear() - Eigen::Matrix3d::Identity()).norm(),
                0.0, 1e-12);
  }
}

TEST(BodyPoseFromLedPoseTest, RejectsNonRigidTransformsNamingThem) {
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d scaled = I;
  scaled.linear() *= 1.01;
  Eigen::Isometry3d reflected = I;
  reflected.linear()(2, 2) = -1.0;
  Eigen::Isometry3d not_finite = I;
  not_finite.translation().x() = std::nan("");
  try {
    BodyPoseFromLedPose(scaled, I, I);
    FAIL() << "a scaled T_WC was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("T_WC"));
  }
  try {
    BodyPoseFromLedPose(I, I, reflected);
    FAIL() << "a reflection T_BT was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("T_BT"));
  }
  EXPECT_THROW(BodyPoseFromLedPose(I, not_finite, I), std::invalid_argument);
  EXPECT_THROW(LedTargetPoseMeasurement(0.0, I, I, Matrix6d::Identity() * std::nan(""), I),
               std::invalid_argument);
}

TEST(LedTargetPoseMeasurementTest, CovarianceFollowsThePerturbationToTheFiltersConvention) {
  // A small tracker-convention perturbation delta = [dt; dphi] of T_CT ((C.9): p_CT + dt,
  // Exp(dphi) R_CT) moves the measurement by r = [p'_WT - p_WT; Log(R_WT^T R'_WT)] (the filter's
  // [n_p (W); n_theta (T)]). With covariance_CT = delta delta^T the mapped covariance must be
  // r r^T: the map is exact for this perturbation (R_WC Exp(d) R_CT = R_WT Exp(R_TC d)), so
  // 1e-11 only leaves room for rounding in Log, while a wrong block (R_CT instead of R_TC, a
  // missing R_WC) is off by ~1e-8, the size of the entries.
  std::mt19937_64 rng(5);
  const Eigen::Isometry3d T_WC = RandomPose(&rng);
  const Eigen::Isometry3d T_CT = RandomPose(&rng);
  const Eigen::Isometry3d T_BT = RandomPose(&rng);
  const Vector6d delta = (Vector6d() << 1e-4, -2e-4, 0.5e-4, 1e-4, 0.7e-4, -1.5e-4).finished();
  Eigen::Isometry3d T_CT_perturbed = T_CT;
  T_CT_perturbed.translation() += delta.head<3>();
  T_CT_perturbed.linear() = control::ExpSo3(delta.tail<3>()) * T_CT.linear();
  const Eigen::Isometry3d T_WT = T_WC * T_CT;
  const Eigen::Isometry3d T_WT_perturbed = T_WC * T_CT_perturbed;
  Vector6d r;
  r << T_WT_perturbed.translation() - T_WT.translation(),
      LogRotation(T_WT.linear().transpose() * T_WT_perturbed.linear());
  const perception::PoseMeasurement z =
      LedTargetPoseMeasurement(1.5, T_WC, T_CT, delta * delta.transpose(), T_BT);
  EXPECT_LT((z.covariance - r * r.transpose()).cwiseAbs().maxCoeff(), 1e-11);
  // The pose is T_WT with the target's extrinsics.
  EXPECT_EQ(z.t_s, 1.5);
  EXPECT_TRUE(z.p_WX.isApprox(T_WT.translation(), 1e-12));
  EXPECT_TRUE(z.q_WX.toRotationMatrix().isApprox(T_WT.linear(), 1e-12));
  EXPECT_TRUE(z.p_BX.isApprox(T_BT.translation(), 1e-12));
  EXPECT_TRUE(z.q_BX.toRotationMatrix().isApprox(T_BT.linear(), 1e-12));
}

TEST(LedHoverAutopilotTest, RejectsBadParameters) {
  const control::VehicleParameters vehicle;
  const auto camera = std::make_shared<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{376.0, 376.0, 375.5, 239.5});
  const perception::LedConfiguration leds = perception::LedConfiguration::Default();
  LedHoverAutopilotParams params;
  EXPECT_NO_THROW(LedHoverAutopilot(vehicle, leds, camera, params));
  EXPECT_THROW(LedHoverAutopilot(vehicle, leds, nullptr, params), std::invalid_argument);
  {
    LedHoverAutopilotParams bad = params;
    bad.camera_id = -1;
    EXPECT_THROW(LedHoverAutopilot(vehicle, leds, camera, bad), std::invalid_argument);
  }
  {
    LedHoverAutopilotParams bad = params;
    bad.T_WC.linear() *= 2.0;
    try {
      LedHoverAutopilot(vehicle, leds, camera, bad);
      FAIL() << "a scaled T_WC was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr("LedHoverAutopilotParams.T_WC"));
    }
  }
  {
    LedHoverAutopilotParams bad = params;
    bad.setpoint.p_W.z() = std::nan("");
    EXPECT_THROW(LedHoverAutopilot(vehicle, leds, camera, bad), std::invalid_argument);
  }
  {
    LedHoverAutopilotParams bad = params;
    bad.hold.integral_gain_per_s3 = -1.0;
    EXPECT_THROW(LedHoverAutopilot(vehicle, leds, camera, bad), std::invalid_argument);
  }
}

TEST(LedHoverAutopilotTest, WithoutFramesItCommandsNothingAndIgnoresOtherCameras) {
  const control::VehicleParameters vehicle;
  const auto camera = std::make_shared<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{376.0, 376.0, 375.5, 239.5});
  LedHoverAutopilotParams params;
  params.camera_id = 1;
  LedHoverAutopilot autopilot(vehicle, perception::LedConfiguration::Default(), camera, params);
  EXPECT_FALSE(autopilot.UsesGroundTruth());
  perception::Frame frame;
  frame.camera_id = 0;  // not the LED camera
  frame.image = cv::Mat(10, 10, CV_8UC1, cv::Scalar(0));
  autopilot.OnFrame(frame);
  EXPECT_EQ(autopilot.counts().frames, 0);
  EXPECT_EQ(autopilot.Step(0.01).kind, perception::AutopilotCommand::Kind::kNone);
  EXPECT_EQ(autopilot.status(), "waiting for pose");
}

}  // namespace
}  // namespace aperture::planning
