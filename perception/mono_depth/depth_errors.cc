#include "perception/mono_depth/depth_errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace aperture::perception {

cv::Mat PatchDepthFromMillimetres(const cv::Mat& depth_mm, const PatchGrid& grid) {
  if (depth_mm.type() != CV_16UC1) {
    throw std::invalid_argument(
        "ground-truth depth: need a 16-bit one-channel image in mm "
        "(as `aperture render` writes depth/*.png); got type " +
        std::to_string(depth_mm.type()));
  }
  const int width = static_cast<int>(grid.cols * grid.frame_patch_px.x() + 0.5);
  const int height = static_cast<int>(grid.rows * grid.frame_patch_px.y() + 0.5);
  if (depth_mm.cols < width || depth_mm.rows < height) {
    throw std::invalid_argument("ground-truth depth: the " + std::to_string(depth_mm.cols) + "x" +
                                std::to_string(depth_mm.rows) + " depth image does not cover the " +
                                std::to_string(width) + "x" + std::to_string(height) +
                                " patch grid of its frame; use the depth rendered with the image");
  }
  cv::Mat truth(grid.rows, grid.cols, CV_32F);
  std::vector<float> values;
  for (int r = 0; r < grid.rows; ++r) {
    const int y0 = int(r * grid.frame_patch_px.y()), y1 = int((r + 1) * grid.frame_patch_px.y());
    for (int c = 0; c < grid.cols; ++c) {
      const int x0 = int(c * grid.frame_patch_px.x()), x1 = int((c + 1) * grid.frame_patch_px.x());
      values.clear();
      for (int y = y0; y < y1; ++y) {
        const std::uint16_t* row = depth_mm.ptr<std::uint16_t>(y);
        for (int x = x0; x < x1; ++x) {
          values.push_back(row[x] == 0 ? std::numeric_limits<float>::infinity()
                                       : 1e-3f * float(row[x]));
        }
      }
      auto middle = values.begin() + values.size() / 2;
      std::nth_element(values.begin(), middle, values.end());
      truth.at<float>(r, c) = *middle;
    }
  }
  return truth;
}

double DepthErrors::MeanLn() const {
  return patches > 0 ? e_ln_sum / patches : std::numeric_limits<double>::quiet_NaN();
}

double DepthErrors::MeanRelative() const {
  return patches > 0 ? e_relative_sum / patches : std::numeric_limits<double>::quiet_NaN();
}

DepthErrors& DepthErrors::operator+=(const DepthErrors& other) {
  e_ln_sum += other.e_ln_sum;
  e_relative_sum += other.e_relative_sum;
  patches += other.patches;
  return *this;
}

DepthErrors CompareDepth(const cv::Mat& estimate_m, const cv::Mat& truth_m, double min_depth_m,
                         double max_depth_m) {
  if (estimate_m.type() != CV_32FC1 || truth_m.type() != CV_32FC1 ||
      estimate_m.size() != truth_m.size()) {
    throw std::invalid_argument(
        "depth errors: estimate and truth must be CV_32FC1 maps of one "
        "size (patch grids of the same frame)");
  }
  if (!(min_depth_m > 0.0) || !(max_depth_m > min_depth_m)) {
    throw std::invalid_argument("depth errors: need 0 < min_depth_m < max_depth_m");
  }
  DepthErrors errors;
  for (int r = 0; r < truth_m.rows; ++r) {
    for (int c = 0; c < truth_m.cols; ++c) {
      const double truth = truth_m.at<float>(r, c);
      if (!std::isfinite(truth)) continue;  // sky: no surface to score
      const double d = std::clamp(truth, min_depth_m, max_depth_m);
      const double d_e = std::clamp(double(estimate_m.at<float>(r, c)), min_depth_m, max_depth_m);
      errors.e_ln_sum += std::abs(std::log(d) - std::log(d_e));
      errors.e_relative_sum += std::abs(d - d_e) / d;
      ++errors.patches;
    }
  }
  return errors;
}

}  // namespace aperture::perception
