#pragma once
// Synthetic infrared images for the LED front-end tests: Gaussian blobs sampled at pixel centres
// on a black background, so a blob's intensity-weighted centroid is its centre up to 8-bit
// rounding.
#include <Eigen/Core>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

namespace aperture::test_support {

inline void AddGaussianBlob(cv::Mat& radiance, const Eigen::Vector2d& px, double sigma_px,
                            double peak) {
  const int r = static_cast<int>(std::ceil(4 * sigma_px));
  for (int y = std::max(0, static_cast<int>(px.y()) - r);
       y <= std::min(radiance.rows - 1, static_cast<int>(px.y()) + r); ++y) {
    for (int x = std::max(0, static_cast<int>(px.x()) - r);
         x <= std::min(radiance.cols - 1, static_cast<int>(px.x()) + r); ++x) {
      const double d2 = (Eigen::Vector2d(x, y) - px).squaredNorm();
      radiance.at<float>(y, x) += static_cast<float>(peak * std::exp(-0.5 * d2 / (sigma_px * sigma_px)));
    }
  }
}

// 8-bit image (saturating) with a blob at every px.
inline cv::Mat BlobImage(int width, int height, const std::vector<Eigen::Vector2d>& px,
                         double sigma_px = 1.5, double peak = 220.0) {
  cv::Mat radiance(height, width, CV_32FC1, cv::Scalar(0));
  for (const auto& p : px) AddGaussianBlob(radiance, p, sigma_px, peak);
  cv::Mat image;
  radiance.convertTo(image, CV_8UC1);
  return image;
}

}  // namespace aperture::test_support
