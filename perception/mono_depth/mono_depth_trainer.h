#pragma once
// Trains the per-patch depth classifier (MonoDepthModel) of seed 003 Sec. III-A from colour
// frames with ground-truth depth: every patch's 102 energies, labelled with the depth label of its
// median ground-truth depth (DepthLabels; sky = farthest label), standardised, and a linear SVM
// fitted with liblinear (L2-regularised L2-loss SVC, one-vs-rest, primal trust-region Newton: the
// fast linear solver the paper chose over an RBF kernel for real time).
#include <cstddef>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "perception/mono_depth/mono_depth_model.h"

namespace aperture::perception {

struct MonoDepthTrainParams {
  MonoDepthFeatureParams features;
  // Label range and count: 0.5 m is about the nearest a trunk gets to a hovering camera, 40 m is
  // past the 30 m deep forest; 16 geometric labels make each bin 24 % wide (ln-width 0.27).
  double min_depth_m = 0.5;
  double max_depth_m = 40.0;
  int labels = 16;
  // Row bands of the per-row prior (MonoDepthModel); 0 = the paper's 102 inputs only.
  int row_bands = 6;
  double log_epsilon = 1e-3;    // ln(eps + E): keeps flat patches (E = 0) finite
  double svm_c = 1.0;           // liblinear C (inputs are standardised, so 1 is the neutral choice)
  double svm_tolerance = 0.01;  // liblinear eps (its default for this solver)
  // Keep every n-th patch of a frame (1 = all): neighbouring patches are strongly correlated.
  int patch_stride = 1;

  void Validate() const;  // std::invalid_argument naming the field
};

struct MonoDepthTrainingReport {
  std::size_t frames = 0;
  std::size_t patches = 0;
  std::vector<std::size_t> patches_per_label;
  double training_accuracy = 0.0;  // fraction of training patches given their own label
  double train_time_s = 0.0;       // liblinear only
};

class MonoDepthTrainer {
 public:
  explicit MonoDepthTrainer(const MonoDepthTrainParams& params = {});

  // One training frame: `bgr` CV_8UC3 and its depth `depth_mm` (CV_16UC1 [mm], 0 = no surface,
  // the same size). Throws std::invalid_argument on a type or size mismatch.
  void AddFrame(const cv::Mat& bgr, const cv::Mat& depth_mm);

  std::size_t PatchCount() const { return labels_.size(); }

  // Throws std::invalid_argument with no patches or fewer than two labels present. Labels no
  // patch had get a score that never wins.
  MonoDepthModel Train(MonoDepthTrainingReport* report = nullptr) const;

 private:
  MonoDepthTrainParams params_;
  MonoDepthFeatureExtractor extractor_;
  DepthLabels depth_labels_;
  std::vector<Eigen::VectorXf> log_energies_;  // per patch, 102
  std::vector<int> bands_;                     // row band per patch
  std::vector<int> labels_;                    // depth label per patch
  std::size_t frames_ = 0;
};

}  // namespace aperture::perception
