#include "perception/quality/image_quality_analyzer.h"

#include <array>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace aperture::perception {
namespace {

void CheckLevel(const char* name, int value) {
  if (value < 0 || value > 255) {
    throw std::invalid_argument(std::string("ImageQualityParams: ") + name + " = " +
                                std::to_string(value) + " is outside [0, 255]");
  }
}

}  // namespace

ImageQualityAnalyzer::ImageQualityAnalyzer(const ImageQualityParams& params) : params_(params) {
  if (params_.histogram_bins < 1 || params_.histogram_bins > 256) {
    throw std::invalid_argument("ImageQualityParams: histogram_bins = " +
                                std::to_string(params_.histogram_bins) + " is outside [1, 256]");
  }
  CheckLevel("over_exposed_level", params_.over_exposed_level);
  CheckLevel("under_exposed_level", params_.under_exposed_level);
}

ImageQuality ImageQualityAnalyzer::Analyze(const cv::Mat& image) {
  if (image.empty()) throw std::invalid_argument("ImageQualityAnalyzer: empty image");
  const cv::Mat* gray = &image;
  if (image.type() == CV_8UC3) {
    cv::cvtColor(image, gray_, cv::COLOR_BGR2GRAY);
    gray = &gray_;
  } else if (image.type() == CV_8UC4) {
    cv::cvtColor(image, gray_, cv::COLOR_BGRA2GRAY);
    gray = &gray_;
  } else if (image.type() != CV_8UC1) {
    throw std::invalid_argument("ImageQualityAnalyzer: image type " +
                                cv::typeToString(image.type()) +
                                " is not supported; give CV_8UC1, CV_8UC3 (BGR) or CV_8UC4");
  }

  // One pass for a full 256-level histogram; everything exposure-related derives from it.
  std::array<std::int64_t, 256> counts{};
  for (int row = 0; row < gray->rows; ++row) {
    const std::uint8_t* pixel = gray->ptr<std::uint8_t>(row);
    for (int col = 0; col < gray->cols; ++col) ++counts[pixel[col]];
  }
  const double pixel_count = static_cast<double>(gray->total());

  ImageQuality quality;
  quality.histogram.assign(params_.histogram_bins, 0.0);
  double intensity_sum = 0.0;
  std::int64_t over = 0;
  std::int64_t under = 0;
  for (int level = 0; level < 256; ++level) {
    const std::int64_t count = counts[level];
    quality.histogram[level * params_.histogram_bins / 256] += static_cast<double>(count);
    intensity_sum += static_cast<double>(level) * static_cast<double>(count);
    if (level >= params_.over_exposed_level) over += count;
    if (level <= params_.under_exposed_level) under += count;
  }
  for (double& bin : quality.histogram) bin /= pixel_count;
  quality.mean_intensity = intensity_sum / pixel_count;
  quality.over_exposed_ratio = static_cast<double>(over) / pixel_count;
  quality.under_exposed_ratio = static_cast<double>(under) / pixel_count;

  cv::Laplacian(*gray, laplacian_, CV_64F);
  cv::Scalar mean;
  cv::Scalar stddev;
  cv::meanStdDev(laplacian_, mean, stddev);
  quality.sharpness_laplacian_var = stddev[0] * stddev[0];
  return quality;
}

}  // namespace aperture::perception
