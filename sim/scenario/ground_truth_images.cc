#include "sim/scenario/ground_truth_images.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "sim/scene/counter_hash.h"

namespace aperture::sim {
namespace {

void RequireType(const cv::Mat& image, int type, const char* what) {
  if (image.type() != type) {
    throw std::invalid_argument(std::string(what) + ": unexpected image type " +
                                std::to_string(image.type()) + " (expected " +
                                std::to_string(type) + ")");
  }
}

}  // namespace

cv::Mat DepthToMillimetres16U(const cv::Mat& depth_C) {
  RequireType(depth_C, CV_32FC1, "DepthToMillimetres16U");
  cv::Mat out(depth_C.size(), CV_16UC1);
  for (int y = 0; y < depth_C.rows; ++y) {
    const float* in = depth_C.ptr<float>(y);
    std::uint16_t* row = out.ptr<std::uint16_t>(y);
    for (int x = 0; x < depth_C.cols; ++x) {
      const double mm = std::round(static_cast<double>(in[x]) * 1000.0);
      row[x] = !std::isfinite(mm) || mm <= 0.0 ? 0
               : mm >= 65535.0                 ? 65535
                                               : static_cast<std::uint16_t>(mm);
    }
  }
  return out;
}

cv::Mat ObjectIdsTo16U(const cv::Mat& object_id) {
  RequireType(object_id, CV_32SC1, "ObjectIdsTo16U");
  cv::Mat out(object_id.size(), CV_16UC1);
  for (int y = 0; y < object_id.rows; ++y) {
    const int* in = object_id.ptr<int>(y);
    std::uint16_t* row = out.ptr<std::uint16_t>(y);
    for (int x = 0; x < object_id.cols; ++x) {
      row[x] = static_cast<std::uint16_t>(std::clamp(in[x], 0, 65535));
    }
  }
  return out;
}

cv::Mat DepthPreview(const cv::Mat& depth_C, double max_depth_m) {
  RequireType(depth_C, CV_32FC1, "DepthPreview");
  cv::Mat gray(depth_C.size(), CV_8UC1);
  cv::Mat valid(depth_C.size(), CV_8UC1);
  for (int y = 0; y < depth_C.rows; ++y) {
    for (int x = 0; x < depth_C.cols; ++x) {
      const float d = depth_C.at<float>(y, x);
      const bool ok = std::isfinite(d) && d > 0.0f;
      valid.at<std::uint8_t>(y, x) = ok ? 255 : 0;
      const double v = ok ? 255.0 * (1.0 - std::min(1.0, d / max_depth_m)) : 0.0;
      gray.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(v);
    }
  }
  cv::Mat color;
  cv::applyColorMap(gray, color, cv::COLORMAP_INFERNO);
  cv::Mat out = cv::Mat::zeros(depth_C.size(), CV_8UC3);
  color.copyTo(out, valid);
  return out;
}

cv::Mat ObjectIdPreview(const cv::Mat& object_id) {
  RequireType(object_id, CV_32SC1, "ObjectIdPreview");
  cv::Mat out(object_id.size(), CV_8UC3);
  for (int y = 0; y < object_id.rows; ++y) {
    for (int x = 0; x < object_id.cols; ++x) {
      const int id = object_id.at<int>(y, x);
      const std::uint64_t h = MixBits(static_cast<std::uint64_t>(id));
      out.at<cv::Vec3b>(y, x) =
          id == 0 ? cv::Vec3b(0, 0, 0)
                  : cv::Vec3b(64 + (h & 0xBF), 64 + ((h >> 8) & 0xBF), 64 + ((h >> 16) & 0xBF));
    }
  }
  return out;
}

}  // namespace aperture::sim
