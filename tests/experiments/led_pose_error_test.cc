// Pose-error metrics of `aperture bench led` against synthetic errors of known size.
#include "experiments/led/led_pose_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace aperture::experiments {
namespace {

Eigen::Isometry3d Pose(const Eigen::Vector3d& p, double angle_rad, const Eigen::Vector3d& axis) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix();
  T.translation() = p;
  return T;
}

TEST(LedPoseErrorTest, PositionAndAngleAxisOrientationErrors) {
  const Eigen::Isometry3d truth = Pose({0.1, -0.2, 1.5}, 0.7, {1.0, 2.0, -0.5});
  // A 3-4-12 mm offset (13 mm) and a 2 deg turn about an arbitrary axis, applied on either side.
  const Eigen::Isometry3d offset = Pose({0.003, 0.004, 0.012}, 2.0 * M_PI / 180.0, {0.3, -1, 2});
  Eigen::Isometry3d estimate = truth;
  estimate.translation() += offset.translation();
  estimate.linear() = offset.linear() * truth.linear();
  const PoseError error = ComputePoseError(estimate, truth);
  EXPECT_NEAR(error.position_m, 0.013, 1e-12);
  EXPECT_NEAR(error.orientation_deg, 2.0, 1e-9);
  // Symmetric in its arguments.
  const PoseError reverse = ComputePoseError(truth, estimate);
  EXPECT_NEAR(reverse.position_m, error.position_m, 1e-12);
  EXPECT_NEAR(reverse.orientation_deg, error.orientation_deg, 1e-9);
  EXPECT_NEAR(ComputePoseError(truth, truth).orientation_deg, 0.0, 1e-12);  // round-off only
}

TEST(LedPoseErrorTest, StatisticsSkipFramesWithoutPose) {
  // Errors 1, 2, 3 cm and 0.5, 1.0, 1.5 deg plus two frames without a pose.
  const std::vector<std::optional<PoseError>> errors{
      PoseError{0.01, 0.5}, std::nullopt, PoseError{0.02, 1.0}, PoseError{0.03, 1.5}, std::nullopt};
  const PoseErrorStatistics stats = ComputePoseErrorStatistics(errors);
  EXPECT_EQ(stats.frames, 5);
  EXPECT_EQ(stats.frames_with_pose, 3);
  EXPECT_NEAR(stats.position_error_mean, 0.02, 1e-12);
  // Population standard deviation of {1, 2, 3} cm: sqrt(2/3) cm.
  EXPECT_NEAR(stats.position_error_std, 0.01 * std::sqrt(2.0 / 3.0), 1e-12);
  EXPECT_NEAR(stats.position_error_max, 0.03, 1e-15);
  EXPECT_NEAR(stats.orientation_error_mean_deg, 1.0, 1e-12);
  EXPECT_NEAR(stats.orientation_error_std_deg, 0.5 * std::sqrt(2.0 / 3.0), 1e-12);
  EXPECT_NEAR(stats.orientation_error_max_deg, 1.5, 1e-15);
  const nlohmann::json json = stats.ToJson();
  EXPECT_EQ(json["frames_with_pose"], 3);
  EXPECT_NEAR(json["position_error_max"].get<double>(), 0.03, 1e-15);
}

TEST(LedPoseErrorTest, NoPoseGivesNullStatistics) {
  const PoseErrorStatistics stats = ComputePoseErrorStatistics({std::nullopt, std::nullopt});
  EXPECT_EQ(stats.frames, 2);
  EXPECT_EQ(stats.frames_with_pose, 0);
  EXPECT_TRUE(std::isnan(stats.position_error_mean));
  EXPECT_TRUE(stats.ToJson()["position_error_mean"].is_null());
}

TEST(LedPoseErrorTest, MahalanobisDistanceUsesTheRefinerParametrisation) {
  const Eigen::Isometry3d truth = Pose({0.0, 0.0, 2.0}, 0.3, {0, 1, 0});
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  covariance.diagonal() << 1e-4, 1e-4, 4e-4, 1e-6, 1e-6, 1e-6;  // sigma 1, 1, 2 cm; 1 mrad
  // 4 cm along z (2 sigma) and 3 mrad about x (3 sigma): d^2 = 4 + 9.
  Eigen::Isometry3d estimate = truth;
  estimate.translation().z() += 0.04;
  estimate.linear() = Eigen::AngleAxisd(0.003, Eigen::Vector3d::UnitX()) * truth.linear();
  EXPECT_NEAR(PoseMahalanobisSquared(estimate, covariance, truth), 13.0, 1e-6);
  // Singular covariance: infinitely improbable.
  EXPECT_TRUE(
      std::isinf(PoseMahalanobisSquared(estimate, Eigen::Matrix<double, 6, 6>::Zero(), truth)));
}

TEST(LedPoseErrorTest, ConfidentWrongPoseNeedsALargeErrorAndATightCovariance) {
  const Eigen::Isometry3d truth = Pose({0.1, 0.0, 1.5}, 0.2, {1, 0, 0});
  Eigen::Isometry3d wrong = truth;
  wrong.translation().x() += 0.05;  // 5 cm off: beyond the 2 cm bound
  const Eigen::Matrix<double, 6, 6> tight = 1e-6 * Eigen::Matrix<double, 6, 6>::Identity();
  const Eigen::Matrix<double, 6, 6> wide = 1e-2 * Eigen::Matrix<double, 6, 6>::Identity();
  EXPECT_TRUE(IsConfidentWrongPose(wrong, tight, truth));  // (5 cm / 1 mm)^2 = 2500 > 22.5
  EXPECT_FALSE(IsConfidentWrongPose(wrong, wide, truth));  // (5 cm / 10 cm)^2 = 0.25
  Eigen::Isometry3d close = truth;
  close.translation().x() += 0.01;  // within the bound: never "wrong"
  EXPECT_FALSE(IsConfidentWrongPose(close, tight, truth));
  Eigen::Isometry3d turned = truth;
  turned.linear() = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()) * truth.linear();  // 5.7 deg
  EXPECT_TRUE(IsConfidentWrongPose(turned, tight, truth));
}

// The hand-eye alignment recovers the markers' offset from exact pairs, and averages noisy ones.
TEST(LedPoseErrorTest, HandEyeRecoversTheMarkerOffset) {
  Eigen::Isometry3d T_CM = Eigen::Isometry3d::Identity();
  T_CM.linear() = Eigen::AngleAxisd(0.05, Eigen::Vector3d(1, -2, 0.5).normalized()).matrix();
  T_CM.translation() = Eigen::Vector3d(0.02, -0.01, 0.03);
  std::vector<Eigen::Isometry3d> T_CT, T_MT, T_CT_noisy;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.002);
  for (int k = 0; k < 200; ++k) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.01 * k, Eigen::Vector3d(0.3, 1, 0.2).normalized()).matrix();
    T.translation() = Eigen::Vector3d(0.1 * std::sin(0.1 * k), 0.05, 1.5 + 0.002 * k);
    T_CT.push_back(T);
    T_MT.push_back(T_CM.inverse() * T);
    Eigen::Isometry3d noisy = T;
    noisy.translation() += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    T_CT_noisy.push_back(noisy);
  }
  const PoseError exact = ComputePoseError(EstimateHandEye(T_CT, T_MT), T_CM);
  EXPECT_LT(exact.position_m, 1e-12);
  EXPECT_LT(exact.orientation_deg, 1e-9);
  // 2 mm per-axis noise averages over 200 pairs to ~0.14 mm.
  EXPECT_LT(ComputePoseError(EstimateHandEye(T_CT_noisy, T_MT), T_CM).position_m, 0.0006);
  EXPECT_THROW(EstimateHandEye({}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::experiments
