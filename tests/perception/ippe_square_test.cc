#include "perception/tags/ippe_square.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>
#include <vector>

#include "control/so3.h"
#include "perception/tags/tag_pose_estimator.h"
#include "tests/support/rotation_error.h"

namespace aperture::perception {
namespace {

using test_support::RotationErrorDeg;

constexpr double kIppeTagSize_m = 0.16;

std::array<Eigen::Vector2d, 4> NormalizedCorners(const Eigen::Isometry3d& T_CT, double noise,
                                                 std::mt19937* rng) {
  std::normal_distribution<double> gauss(0.0, noise);
  std::array<Eigen::Vector2d, 4> corners;
  for (int k = 0; k < 4; ++k) {
    corners[k] = (T_CT * TagCorner(k, kIppeTagSize_m)).hnormalized();
    if (noise > 0.0) corners[k] += Eigen::Vector2d(gauss(*rng), gauss(*rng));
  }
  return corners;
}

// A random pose in front of the camera: 0.3-4 m away, anywhere in a 100 deg field of view,
// tilted up to 75 deg from facing the camera, any roll about the tag's normal.
Eigen::Isometry3d RandomTagPose(std::mt19937* rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double distance_m = 0.3 + 3.7 * (0.5 + 0.5 * unit(*rng));
  Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
  T_CT.translation() = distance_m * Eigen::Vector3d(1.2 * unit(*rng), 1.2 * unit(*rng), 1.0);
  const double tilt_rad = 75.0 * M_PI / 180.0 * (0.5 + 0.5 * unit(*rng));
  const double tilt_axis_rad = M_PI * unit(*rng);
  T_CT.linear() = control::ExpSo3(tilt_rad * Eigen::Vector3d(std::cos(tilt_axis_rad),
                                                             std::sin(tilt_axis_rad), 0)) *
                  control::ExpSo3(Eigen::Vector3d(0.0, 0.0, M_PI * unit(*rng)));
  return T_CT;
}

// Noise-free corners: one of the two solutions is the true pose to round-off, for any pose.
TEST(IppeSquareTest, OneSolutionIsTheTruePoseFromExactCorners) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::Isometry3d T_CT = RandomTagPose(&rng);
    const auto solutions = IppeSquare(NormalizedCorners(T_CT, 0.0, &rng), kIppeTagSize_m);
    ASSERT_TRUE(solutions) << "trial " << trial;
    double best_deg = 1e9, best_m = 1e9;
    for (const Eigen::Isometry3d& solution : *solutions) {
      EXPECT_NEAR(
          (solution.linear().transpose() * solution.linear() - Eigen::Matrix3d::Identity()).norm(),
          0.0, 1e-9);
      if (RotationErrorDeg(solution, T_CT) < best_deg) {
        best_deg = RotationErrorDeg(solution, T_CT);
        best_m = (solution.translation() - T_CT.translation()).norm();
      }
    }
    EXPECT_LT(best_deg, 1e-6) << "trial " << trial;
    EXPECT_LT(best_m, 1e-8 * T_CT.translation().norm()) << "trial " << trial;
  }
}

// The other solution is the mirror image: the tag centre sits on the same ray and the normal is
// reflected about it, so the two tilts differ except head-on.
TEST(IppeSquareTest, TheSecondSolutionIsTheMirroredTilt) {
  Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
  T_CT.translation() = Eigen::Vector3d(0.0, 0.0, 2.0);
  T_CT.linear() = control::ExpSo3(Eigen::Vector3d(0.5, 0.0, 0.0));
  std::mt19937 rng(1);
  const auto solutions = IppeSquare(NormalizedCorners(T_CT, 0.0, &rng), kIppeTagSize_m);
  ASSERT_TRUE(solutions);
  const Eigen::Vector3d normal_y((*solutions)[0].linear().col(2).y(),
                                 (*solutions)[1].linear().col(2).y(), 0.0);
  // Normals n = R e_z: one tilted by +0.5 rad about x_C (n_y = -sin 0.5), the other by about
  // -0.5 rad (the weak-perspective mirror; exact only in the limit).
  EXPECT_NEAR(std::min(normal_y.x(), normal_y.y()), -std::sin(0.5), 1e-9);
  EXPECT_GT(std::max(normal_y.x(), normal_y.y()), 0.3);
  // Head-on the two coincide.
  T_CT.linear().setIdentity();
  const auto head_on = IppeSquare(NormalizedCorners(T_CT, 0.0, &rng), kIppeTagSize_m);
  ASSERT_TRUE(head_on);
  EXPECT_LT(RotationErrorDeg((*head_on)[0], (*head_on)[1]), 1e-6);
}

// With noisy corners the closed form is OpenCV's SOLVEPNP_IPPE_SQUARE (the same equations):
// the two solution sets agree.
TEST(IppeSquareTest, AgreesWithOpenCvOnNoisyCorners) {
  std::mt19937 rng(5);
  std::vector<cv::Point3d> object;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d p_T = TagCorner(k, kIppeTagSize_m);
    object.emplace_back(p_T.x(), p_T.y(), 0.0);
  }
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Isometry3d T_CT = RandomTagPose(&rng);
    const std::array<Eigen::Vector2d, 4> corners = NormalizedCorners(T_CT, 2e-3, &rng);
    const auto ours = IppeSquare(corners, kIppeTagSize_m);
    ASSERT_TRUE(ours);
    std::vector<cv::Point2d> image;
    for (const Eigen::Vector2d& corner : corners) image.emplace_back(corner.x(), corner.y());
    std::vector<cv::Mat> rvecs, tvecs;
    ASSERT_EQ(cv::solvePnPGeneric(object, image, cv::Matx33d::eye(), cv::noArray(), rvecs, tvecs,
                                  false, cv::SOLVEPNP_IPPE_SQUARE),
              2);
    for (int s = 0; s < 2; ++s) {
      Eigen::Isometry3d theirs = Eigen::Isometry3d::Identity();
      theirs.linear() = control::ExpSo3(
          Eigen::Vector3d(rvecs[s].at<double>(0), rvecs[s].at<double>(1), rvecs[s].at<double>(2)));
      theirs.translation() =
          Eigen::Vector3d(tvecs[s].at<double>(0), tvecs[s].at<double>(1), tvecs[s].at<double>(2));
      double closest_deg = 1e9, closest_m = 1e9;
      for (const Eigen::Isometry3d& solution : *ours) {
        if (RotationErrorDeg(solution, theirs) < closest_deg) {
          closest_deg = RotationErrorDeg(solution, theirs);
          closest_m = (solution.translation() - theirs.translation()).norm();
        }
      }
      EXPECT_LT(closest_deg, 1e-6) << "trial " << trial;
      EXPECT_LT(closest_m, 1e-6 * theirs.translation().norm()) << "trial " << trial;
    }
  }
}

TEST(IppeSquareTest, RefusesCollinearCorners) {
  std::array<Eigen::Vector2d, 4> corners = {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.1, 0.0),
                                            Eigen::Vector2d(0.2, 0.0), Eigen::Vector2d(0.0, 0.1)};
  EXPECT_FALSE(IppeSquare(corners, kIppeTagSize_m));
}

}  // namespace
}  // namespace aperture::perception
