#include "perception/led/led_detector.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "led_test_images.h"
#include "perception/camera/radtan_camera.h"

namespace aperture::perception {
namespace {

using test_support::BlobImage;

class LedDetectorTest : public ::testing::Test {
 protected:
  RadTanCamera camera_{752, 480, PinholeIntrinsics{420.0, 420.0, 375.5, 239.5},
                       RadTanDistortion{-0.28, 0.07, 0.0005, -0.0003, 0.0, false}};
};

// Nearest detection to px, or nullptr.
const LedDetection* Nearest(const LedDetectionResult& result, const Eigen::Vector2d& px) {
  const LedDetection* best = nullptr;
  for (const auto& d : result.detections) {
    if (!best || (d.px - px).norm() < (best->px - px).norm()) best = &d;
  }
  return best;
}

TEST_F(LedDetectorTest, CentroidsAndBearingsOfBlobs) {
  const std::vector<Eigen::Vector2d> centres{
      {100.3, 50.7}, {375.5, 239.5}, {600.25, 400.8}, {700.9, 30.1}, {20.6, 460.2}};
  LedDetector detector;
  const LedDetectionResult result = detector.Detect(BlobImage(752, 480, centres), camera_);
  ASSERT_EQ(result.detections.size(), centres.size());
  EXPECT_FALSE(result.capped);
  for (const auto& centre : centres) {
    const LedDetection* d = Nearest(result, centre);
    // The threshold (C.1) cuts the blob's tails symmetrically; 8-bit rounding and the
    // sampling of a 1.5 px Gaussian leave < 0.05 px.
    EXPECT_LT((d->px - centre).norm(), 0.05) << centre.transpose();
    // Undistorted through the camera model: the bearing reprojects onto the centroid.
    Eigen::Vector2d reprojected;
    ASSERT_TRUE(camera_.Project(d->f_C, &reprojected));
    EXPECT_LT((reprojected - d->px).norm(), 1e-6);
    EXPECT_NEAR(d->f_C.norm(), 1.0, 1e-12);
  }
}

TEST_F(LedDetectorTest, RoisLimitTheSearch) {
  const std::vector<Eigen::Vector2d> centres{{100.3, 50.7}, {375.5, 239.5}, {600.25, 400.8}};
  LedDetector detector;
  const LedDetectionResult result = detector.Detect(
      BlobImage(752, 480, centres), camera_,
      {cv::Rect(360, 225, 31, 31), cv::Rect(370, 230, 31, 31), cv::Rect(580, 380, 40, 40)});
  ASSERT_EQ(result.detections.size(), 2u);
  EXPECT_LT((Nearest(result, centres[1])->px - centres[1]).norm(), 0.05);
  EXPECT_LT((Nearest(result, centres[2])->px - centres[2]).norm(), 0.05);
}

TEST_F(LedDetectorTest, FiltersHotPixelsStreaksAndLargeAreas) {
  cv::Mat image = BlobImage(752, 480, {{300.4, 200.6}});
  image.at<std::uint8_t>(50, 50) = 255;                                     // hot pixel
  cv::line(image, {400, 100}, {470, 110}, cv::Scalar(250), 2);              // streak
  cv::circle(image, {600, 300}, 40, cv::Scalar(250), cv::FILLED);           // lamp
  LedDetector detector;
  const LedDetectionResult result = detector.Detect(image, camera_);
  ASSERT_EQ(result.detections.size(), 1u);
  EXPECT_LT((result.detections[0].px - Eigen::Vector2d(300.4, 200.6)).norm(), 0.05);
}

TEST_F(LedDetectorTest, CapsTheBlobCountWithAWarning) {
  std::vector<Eigen::Vector2d> centres;
  for (int i = 0; i < 50; ++i) centres.emplace_back(40.0 + 70.0 * (i % 10), 40.0 + 80.0 * (i / 10));
  LedDetector detector;
  const LedDetectionResult result = detector.Detect(BlobImage(752, 480, centres), camera_);
  EXPECT_EQ(result.blobs_found, 50);
  EXPECT_TRUE(result.capped);
  EXPECT_EQ(static_cast<int>(result.detections.size()), detector.params().max_blobs);
  EXPECT_THAT(result.warning, ::testing::HasSubstr("50 bright blobs"));
}

TEST_F(LedDetectorTest, RejectsBadInputNamingIt) {
  LedDetector detector;
  EXPECT_THROW(detector.Detect(cv::Mat(), camera_), std::invalid_argument);
  EXPECT_THAT([&] { detector.Detect(cv::Mat::zeros(240, 376, CV_8UC1), camera_); },
              ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("376x240")));
  LedDetectorParams params;
  params.max_blobs = 2;
  EXPECT_THAT([&] { LedDetector{params}; },
              ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("max_blobs")));
  EXPECT_TRUE(detector.Detect(cv::Mat::zeros(480, 752, CV_8UC1), camera_).detections.empty());
}

}  // namespace
}  // namespace aperture::perception
