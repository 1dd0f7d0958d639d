#include "perception/mono_depth/mono_depth_estimator.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace aperture::perception {

// Generated at configure time from the shipped model file (CMakeLists.txt).
const char* DefaultMonoDepthModelText();

MonoDepthEstimator::MonoDepthEstimator(MonoDepthModel model)
    : model_(std::move(model)), extractor_(model_.feature_params()) {}

MonoDepthEstimate MonoDepthEstimator::Estimate(const cv::Mat& bgr) {
  MonoDepthEstimate estimate;
  const Eigen::MatrixXf energies = extractor_.Extract(bgr);
  estimate.grid = extractor_.Grid(bgr.size());
  estimate.labels = model_.PredictLabels(energies, estimate.grid);
  estimate.depth_m.create(estimate.labels.size(), CV_32F);
  for (int r = 0; r < estimate.labels.rows; ++r) {
    for (int c = 0; c < estimate.labels.cols; ++c) {
      estimate.depth_m.at<float>(r, c) =
          float(model_.labels().DepthOf(estimate.labels.at<int>(r, c)));
    }
  }
  return estimate;
}

cv::Mat DepthImageMillimetres(const MonoDepthEstimate& estimate, const cv::Size& frame_size) {
  cv::Mat depth_mm = cv::Mat::zeros(frame_size, CV_16U);
  const PatchGrid& grid = estimate.grid;
  for (int r = 0; r < grid.rows; ++r) {
    const int y0 = int(r * grid.frame_patch_px.y());
    const int y1 = std::min(frame_size.height, int((r + 1) * grid.frame_patch_px.y()));
    for (int c = 0; c < grid.cols; ++c) {
      const int x0 = int(c * grid.frame_patch_px.x());
      const int x1 = std::min(frame_size.width, int((c + 1) * grid.frame_patch_px.x()));
      const double mm =
          std::clamp(std::round(1000.0 * estimate.depth_m.at<float>(r, c)), 1.0, 65535.0);
      depth_mm(cv::Rect(x0, y0, x1 - x0, y1 - y0)).setTo(cv::Scalar(mm));
    }
  }
  return depth_mm;
}

MonoDepthModel DefaultMonoDepthModel() {
  std::istringstream in(DefaultMonoDepthModelText());
  return MonoDepthModel::Parse(in, "built-in forest_mono_depth.model");
}

}  // namespace aperture::perception
