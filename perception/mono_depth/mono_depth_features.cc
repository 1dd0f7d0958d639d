#include "perception/mono_depth/mono_depth_features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace aperture::perception {
namespace {

// Laws' 1-D masks (L3 level, E3 edge, S3 spot); L3 is normalised so that L3 L3 is a local mean.
const cv::Mat& LawsMask(int which) {
  static const std::array<cv::Mat, 3> masks{cv::Mat(cv::Matx13f(0.25f, 0.5f, 0.25f)),
                                            cv::Mat(cv::Matx13f(-0.5f, 0.0f, 0.5f)),
                                            cv::Mat(cv::Matx13f(-0.25f, 0.5f, -0.25f))};
  return masks[which];
}
// 5-tap binomial Gaussian and its derivative: the x/y derivative pair steers to any angle.
const cv::Mat kGauss5 = cv::Mat(cv::Matx<float, 1, 5>(1, 4, 6, 4, 1)) / 16.0f;
const cv::Mat kDeriv5 = cv::Mat(cv::Matx<float, 1, 5>(-1, -2, 0, 2, 1)) / 8.0f;

}  // namespace

void MonoDepthFeatureParams::Validate() const {
  if (work_width_px < 16) {
    throw std::invalid_argument("mono_depth features: work_width_px = " +
                                std::to_string(work_width_px) + " must be at least 16");
  }
  if (patch_px < 2 || patch_px > work_width_px) {
    throw std::invalid_argument("mono_depth features: patch_px = " + std::to_string(patch_px) +
                                " must be in [2, work_width_px]");
  }
  if (scale_factor < 2) {
    throw std::invalid_argument("mono_depth features: scale_factor = " +
                                std::to_string(scale_factor) + " must be at least 2");
  }
}

MonoDepthFeatureExtractor::MonoDepthFeatureExtractor(const MonoDepthFeatureParams& params)
    : params_(params) {
  params_.Validate();
}

PatchGrid MonoDepthFeatureExtractor::Grid(const cv::Size& frame_size) const {
  PatchGrid grid;
  grid.work_width_px = params_.work_width_px;
  grid.work_height_px = static_cast<int>(std::lround(
      double(frame_size.height) * params_.work_width_px / std::max(1, frame_size.width)));
  grid.cols = grid.work_width_px / params_.patch_px;
  grid.rows = grid.work_height_px / params_.patch_px;
  if (frame_size.width <= 0 || grid.rows < 1 || grid.cols < 1) {
    throw std::invalid_argument(
        "mono_depth features: a " + std::to_string(frame_size.width) + "x" +
        std::to_string(frame_size.height) + " frame is smaller than one patch (patch_px " +
        std::to_string(params_.patch_px) + " at work_width_px " +
        std::to_string(params_.work_width_px) + "); use a larger frame or smaller patch_px");
  }
  const double frame_per_work = double(frame_size.width) / params_.work_width_px;
  grid.frame_patch_px = Eigen::Vector2d::Constant(params_.patch_px * frame_per_work);
  return grid;
}

Eigen::MatrixXf MonoDepthFeatureExtractor::Extract(const cv::Mat& bgr) {
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    throw std::invalid_argument(
        "mono_depth features: need a non-empty 8-bit BGR colour image (CV_8UC3) for the haze "
        "cues; got " +
        std::string(bgr.empty() ? "an empty image"
                                : std::to_string(bgr.channels()) + "-channel type " +
                                      std::to_string(bgr.type())) +
        ". Read colour frames (aperture run --color; cameras.<name>.color: true when rendering)");
  }
  const PatchGrid grid = Grid(bgr.size());
  cv::resize(bgr, work_bgr_, cv::Size(grid.work_width_px, grid.work_height_px), 0, 0,
             cv::INTER_AREA);
  Eigen::MatrixXf features(grid.rows * grid.cols, kFeatures);
  cv::Mat level_bgr = work_bgr_;
  for (int scale = 0; scale < kScales; ++scale) {
    if (scale > 0) {
      const cv::Size size(std::max(1, level_bgr.cols / params_.scale_factor),
                          std::max(1, level_bgr.rows / params_.scale_factor));
      cv::Mat smaller;
      cv::resize(level_bgr, smaller, size, 0, 0, cv::INTER_AREA);
      level_bgr = smaller;
    }
    // 8-bit conversion: Cr, Cb centred on 128 (a gray patch has Cr = Cb = 128).
    cv::cvtColor(level_bgr, ycrcb8_, cv::COLOR_BGR2YCrCb);
    ycrcb8_.convertTo(ycrcb_, CV_32FC3);
    cv::Mat channels[3];
    cv::split(ycrcb_, channels);
    AddScale(scale, channels[0], channels[1], channels[2], grid, features);
  }
  return features;
}

void MonoDepthFeatureExtractor::AddScale(int scale, const cv::Mat& y, const cv::Mat& cr,
                                         const cv::Mat& cb, const PatchGrid& grid,
                                         Eigen::MatrixXf& features) {
  // Window of each patch at this level: patch_px level pixels centred on the patch centre.
  const double to_level = std::pow(double(params_.scale_factor), -scale);
  const int p = params_.patch_px;
  const auto window = [&](int index, int extent_px) {
    const double centre = (index + 0.5) * p * to_level;
    const int lo = std::clamp(int(std::lround(centre - 0.5 * p)), 0, std::max(0, extent_px - 1));
    const int hi = std::clamp(lo + p, lo + 1, extent_px);
    return std::pair<int, int>(lo, hi);
  };
  std::vector<std::pair<int, int>> cols(grid.cols), rows(grid.rows);
  for (int c = 0; c < grid.cols; ++c) cols[c] = window(c, y.cols);
  for (int r = 0; r < grid.rows; ++r) rows[r] = window(r, y.rows);

  // One filter response -> its two energies (k = 1, 2) as window means (Sec. III-A E_i(n)).
  const auto add_energies = [&](int filter, const cv::Mat& response) {
    for (int k = 1; k <= 2; ++k) {
      if (k == 1) {
        energy_ = cv::abs(response);
      } else {
        cv::multiply(response, response, energy_);
      }
      cv::integral(energy_, integral_, CV_64F);
      const int column = scale * kFeaturesPerScale + (k - 1) * kFilters + filter;
      for (int r = 0; r < grid.rows; ++r) {
        const auto [y0, y1] = rows[r];
        const double* top = integral_.ptr<double>(y0);
        const double* bottom = integral_.ptr<double>(y1);
        for (int c = 0; c < grid.cols; ++c) {
          const auto [x0, x1] = cols[c];
          const double sum = bottom[x1] - bottom[x0] - top[x1] + top[x0];
          features(r * grid.cols + c, column) = float(sum / double((x1 - x0) * (y1 - y0)));
        }
      }
    }
  };
  // 9 Laws' masks on intensity (texture energy).
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      cv::sepFilter2D(y, response_, CV_32F, LawsMask(j), LawsMask(i), cv::Point(-1, -1), 0.0,
                      cv::BORDER_REFLECT);
      add_energies(3 * i + j, response_);
    }
  }
  // Local averages of the colour channels (haze).
  cv::sepFilter2D(cr, response_, CV_32F, LawsMask(0), LawsMask(0), cv::Point(-1, -1), 0.0,
                  cv::BORDER_REFLECT);
  add_energies(9, response_);
  cv::sepFilter2D(cb, response_, CV_32F, LawsMask(0), LawsMask(0), cv::Point(-1, -1), 0.0,
                  cv::BORDER_REFLECT);
  add_energies(10, response_);
  // Six oriented edge filters (texture gradient): cos(theta) G_x + sin(theta) G_y.
  cv::Mat gx, gy;
  cv::sepFilter2D(y, gx, CV_32F, kDeriv5, kGauss5, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
  cv::sepFilter2D(y, gy, CV_32F, kGauss5, kDeriv5, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
  for (int o = 0; o < 6; ++o) {
    const double theta = o * M_PI / 6.0;
    cv::addWeighted(gx, std::cos(theta), gy, std::sin(theta), 0.0, response_);
    add_energies(11 + o, response_);
  }
}

}  // namespace aperture::perception
