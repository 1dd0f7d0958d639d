#include "perception/io/frame_source.h"

#include <cmath>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace aperture::perception {

void FrameSource::RecordSkip(const std::string& item, const std::string& reason) {
  skipped_.push_back({item, reason});
  std::cerr << "warning: " << Describe() << ": skipping " << item << ": " << reason << '\n';
}

void CheckFrameSourceOptions(const FrameSourceOptions& options) {
  if (!(options.fps == 0.0 || (std::isfinite(options.fps) && options.fps > 0.0))) {
    throw std::invalid_argument("frame rate fps = " + std::to_string(options.fps) +
                                " is invalid; pass a positive rate in Hz or 0 for unset");
  }
}

cv::Mat ConvertToColorMode(const cv::Mat& image, ColorMode mode) {
  if (image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3 &&
                                 image.channels() != 4)) {
    throw std::invalid_argument("image of OpenCV type " + std::to_string(image.type()) +
                                " cannot be a frame; frames are 8-bit gray, BGR or BGRA");
  }
  const int target_channels = mode == ColorMode::kGray ? 1 : 3;
  if (image.channels() == target_channels) return image;
  int code = 0;
  if (mode == ColorMode::kGray) {
    code = image.channels() == 3 ? cv::COLOR_BGR2GRAY : cv::COLOR_BGRA2GRAY;
  } else {
    code = image.channels() == 1 ? cv::COLOR_GRAY2BGR : cv::COLOR_BGRA2BGR;
  }
  cv::Mat converted;
  cv::cvtColor(image, converted, code);
  return converted;
}

std::string ToString(ColorMode mode) { return mode == ColorMode::kGray ? "gray" : "color"; }

}  // namespace aperture::perception
