#include "perception/led/led_pose_refiner.h"

#include <gtest/gtest.h>

#include <random>

#include "control/so3.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/camera/radtan_camera.h"
#include "perception/led/led_configuration.h"

namespace aperture::perception {
namespace {

std::unique_ptr<CameraModel> MakeLedCamera(bool distorted) {
  const PinholeIntrinsics k{420.0, 420.0, 375.5, 239.5};
  if (!distorted) return std::make_unique<PinholeCamera>(752, 480, k);
  return std::make_unique<RadTanCamera>(752, 480, k,
                                        RadTanDistortion{-0.28, 0.07, 0.0005, -0.0003, 0.0, false});
}

Eigen::Isometry3d TruePose() {
  Eigen::Isometry3d T_CT =
      control::ExpSe3((control::Vector6d() << 0, 0, 0, 0.3, -0.5, 2.8).finished());
  T_CT.translation() = Eigen::Vector3d(0.1, -0.05, 1.0);
  return T_CT;
}

// The perturbation of the header: (Exp(delta_phi) R, p + delta_t).
Eigen::Isometry3d PerturbedPose(const Eigen::Isometry3d& T, const control::Vector6d& delta) {
  Eigen::Isometry3d result = T;
  result.translation() += delta.head<3>();
  result.linear() = control::ExpSo3(delta.tail<3>()) * T.linear();
  return result;
}

class LedPoseRefinerTest : public ::testing::TestWithParam<bool> {
 protected:
  std::unique_ptr<CameraModel> camera_ = MakeLedCamera(GetParam());
  LedConfiguration configuration_ = LedConfiguration::Default();
};

TEST_P(LedPoseRefinerTest, JacobianMatchesNumericDifferentiation) {
  const Eigen::Isometry3d T_CT = TruePose();
  for (const Eigen::Vector3d& p_T : configuration_.p_T()) {
    Eigen::Vector2d px;
    Eigen::Matrix<double, 2, 6> J;
    ASSERT_TRUE(ProjectLed(*camera_, T_CT, p_T, &px, &J));
    Eigen::Matrix<double, 2, 6> J_numeric;
    const double h = 1e-6;  // central differences: O(h^2) truncation, ~1e-10 px rounding / h
    for (int k = 0; k < 6; ++k) {
      Eigen::Vector2d plus, minus;
      ASSERT_TRUE(
          ProjectLed(*camera_, PerturbedPose(T_CT, h * control::Vector6d::Unit(k)), p_T, &plus));
      ASSERT_TRUE(
          ProjectLed(*camera_, PerturbedPose(T_CT, -h * control::Vector6d::Unit(k)), p_T, &minus));
      J_numeric.col(k) = (plus - minus) / (2 * h);
    }
    // Entries are O(100-400) px per m or rad; 1e-4 px is the numeric noise floor above.
    EXPECT_LT((J - J_numeric).cwiseAbs().maxCoeff(), 1e-4) << J << "\n" << J_numeric;
  }
}

TEST_P(LedPoseRefinerTest, ConvergesToTheTruePoseFromAPerturbedStart) {
  const Eigen::Isometry3d T_CT = TruePose();
  std::vector<Eigen::Vector2d> px;
  for (const auto& p_T : configuration_.p_T()) {
    px.emplace_back();
    ASSERT_TRUE(camera_->Project(T_CT * p_T, &px.back()));
  }
  const control::Vector6d offset =
      (control::Vector6d() << 0.03, -0.02, 0.1, 0.05, -0.04, 0.06).finished();
  const LedPoseRefinement refined =
      RefineLedPose(*camera_, configuration_.p_T(), px, PerturbedPose(T_CT, offset));
  ASSERT_TRUE(refined.valid);
  EXPECT_LT((refined.T_CT.matrix() - T_CT.matrix()).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT(refined.rms_px, 1e-6);
  EXPECT_LE(refined.iterations, 10);
}

TEST_P(LedPoseRefinerTest, CovarianceMatchesTheEmpiricalSpreadOfNoisyEstimates) {
  const Eigen::Isometry3d T_CT = TruePose();
  std::vector<Eigen::Vector2d> px_true;
  for (const auto& p_T : configuration_.p_T()) {
    px_true.emplace_back();
    ASSERT_TRUE(camera_->Project(T_CT * p_T, &px_true.back()));
  }
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);  // Sigma_D = 1 px^2, as the refiner assumes
  constexpr int kTrials = 1000;
  Matrix6d empirical = Matrix6d::Zero();
  Matrix6d predicted = Matrix6d::Zero();
  for (int trial = 0; trial < kTrials; ++trial) {
    std::vector<Eigen::Vector2d> px = px_true;
    for (auto& p : px) p += Eigen::Vector2d(noise(rng), noise(rng));
    const LedPoseRefinement refined = RefineLedPose(*camera_, configuration_.p_T(), px, T_CT);
    ASSERT_TRUE(refined.valid);
    control::Vector6d error;
    error.head<3>() = refined.T_CT.translation() - T_CT.translation();
    error.tail<3>() = control::LogSo3(refined.T_CT.linear() * T_CT.linear().transpose());
    empirical += error * error.transpose() / kTrials;
    predicted += refined.covariance / kTrials;
  }
  // A variance estimated from 1000 samples has a relative standard deviation of
  // sqrt(2 / 1000) = 4.5 %; 20 % (the brief) is > 4 sigma and covers the small nonlinearity.
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(empirical(k, k) / predicted(k, k), 1.0, 0.2) << "component " << k;
  }
  // Correlations (e.g. depth vs tilt) must agree too: compare the whole matrix in the metric of
  // the prediction.
  const Eigen::LLT<Matrix6d> llt(predicted);
  const Matrix6d L_inv = llt.matrixL().solve(Matrix6d::Identity());
  const Matrix6d whitened = L_inv * empirical * L_inv.transpose();
  EXPECT_LT((whitened - Matrix6d::Identity()).cwiseAbs().maxCoeff(), 0.2) << whitened;
}

TEST_P(LedPoseRefinerTest, TooFewOrUnprojectablePointsGiveNoPose) {
  const Eigen::Isometry3d T_CT = TruePose();
  std::vector<Eigen::Vector3d> p_T(configuration_.p_T().begin(), configuration_.p_T().begin() + 2);
  EXPECT_FALSE(RefineLedPose(*camera_, p_T, {{1, 1}, {2, 2}}, T_CT).valid);
  Eigen::Isometry3d behind = T_CT;
  behind.translation().z() = -1.5;  // target behind the camera
  std::vector<Eigen::Vector2d> px(configuration_.size(), Eigen::Vector2d(300, 200));
  EXPECT_FALSE(RefineLedPose(*camera_, configuration_.p_T(), px, behind).valid);
}

INSTANTIATE_TEST_SUITE_P(PinholeAndRadTan, LedPoseRefinerTest, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "RadTan" : "Pinhole"; });

}  // namespace
}  // namespace aperture::perception
