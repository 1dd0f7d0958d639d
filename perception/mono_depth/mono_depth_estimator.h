#pragma once
// Monocular depth of one colour frame (seed 003 Sec. III-A): patch energies
// (MonoDepthFeatureExtractor) classified by a trained MonoDepthModel into a depth per patch.
#include <opencv2/core/mat.hpp>

#include "perception/mono_depth/mono_depth_model.h"

namespace aperture::perception {

struct MonoDepthEstimate {
  PatchGrid grid;
  cv::Mat depth_m;  // CV_32FC1 grid.rows x grid.cols, D_E per patch [m]
  cv::Mat labels;   // CV_32SC1, the label behind each depth
};

class MonoDepthEstimator {
 public:
  explicit MonoDepthEstimator(MonoDepthModel model);

  // `bgr`: CV_8UC3 frame (std::invalid_argument otherwise, see MonoDepthFeatureExtractor).
  // Not safe to call concurrently on one estimator (reused buffers).
  MonoDepthEstimate Estimate(const cv::Mat& bgr);

  const MonoDepthModel& model() const { return model_; }

 private:
  MonoDepthModel model_;
  MonoDepthFeatureExtractor extractor_;
};

// The patch depths as a frame-sized 16-bit depth image in millimetres (each patch's pixels get
// its depth; the uncovered right/bottom remainder is 0 = no estimate), the format of the
// renderer's depth/*.png.
cv::Mat DepthImageMillimetres(const MonoDepthEstimate& estimate, const cv::Size& frame_size);

// The model shipped in the repository (perception/mono_depth/models/forest_mono_depth.model,
// compiled in), trained on rendered `forest` frames by `aperture train mono_depth`.
MonoDepthModel DefaultMonoDepthModel();

}  // namespace aperture::perception
