#pragma once
// The trained per-patch depth classifier of seed 003 Sec. III-A: a multi-class linear SVM over the
// 102 patch features (MonoDepthFeatureExtractor), one weight row per depth label (DepthLabels);
// a patch gets the label of the largest score, i.e. the depth of that label's centre.
//
// Inputs of the linear scores, per patch: z_j = (ln(log_epsilon + E_j) - mean_j) / std_j for the
// 102 energies (the energies span decades, so the classifier sees their logarithms, standardised
// over the training set), then row_bands one-hot entries for the band of image rows the patch
// lies in (Saxena et al. [17] learn parameters per image row, since a forward camera sees the
// ground near at the bottom and far at the horizon; 0 = the paper's 102 inputs only), then 1
// (bias).
//
// Text file, version header first:
//   aperture-mono-depth-model 1
//   features <work_width_px> <patch_px> <scale_factor> <log_epsilon>
//   labels <N> <edge_0> ... <edge_N>          [m]
//   row_bands <R>
//   mean <102 numbers>
//   std <102 numbers>
//   weights <N> <102 + R + 1>
//   <one line of scores' weights per label, near to far>
// Lines starting with '#' are comments. Load throws std::invalid_argument naming the file, the
// line and what was expected (another version, a truncated file, a wrong count).
#include <Eigen/Core>
#include <istream>
#include <opencv2/core/mat.hpp>
#include <string>

#include "perception/mono_depth/depth_labels.h"
#include "perception/mono_depth/mono_depth_features.h"

namespace aperture::perception {

class MonoDepthModel {
 public:
  static constexpr int kVersion = 1;
  static constexpr const char* kMagic = "aperture-mono-depth-model";

  // weights: labels.Count() rows x (102 + row_bands + 1) columns. Throws std::invalid_argument on
  // inconsistent sizes, a non-positive std or non-finite numbers.
  MonoDepthModel(const MonoDepthFeatureParams& features, double log_epsilon, DepthLabels labels,
                 int row_bands, Eigen::VectorXf mean, Eigen::VectorXf std_dev,
                 Eigen::MatrixXf weights);

  static MonoDepthModel Load(const std::string& path);
  // `source` names the stream in error messages.
  static MonoDepthModel Parse(std::istream& in, const std::string& source);
  void Save(const std::string& path) const;
  void Write(std::ostream& out) const;

  // Classifier inputs (the z above, with row one-hot and bias): patches x InputSize().
  Eigen::MatrixXf Inputs(const Eigen::MatrixXf& energies, const PatchGrid& grid) const;
  // Label per patch, CV_32SC1 grid.rows x grid.cols, from the energies of Extract().
  cv::Mat PredictLabels(const Eigen::MatrixXf& energies, const PatchGrid& grid) const;
  // Depth per patch [m], CV_32FC1 grid.rows x grid.cols: the centre of the predicted label.
  cv::Mat PredictDepth(const Eigen::MatrixXf& energies, const PatchGrid& grid) const;

  int InputSize() const { return static_cast<int>(weights_.cols()); }
  const MonoDepthFeatureParams& feature_params() const { return features_; }
  const DepthLabels& labels() const { return labels_; }
  int row_bands() const { return row_bands_; }
  double log_epsilon() const { return log_epsilon_; }
  const Eigen::MatrixXf& weights() const { return weights_; }

  // Feature standardisation (ln(eps + E) - mean) / std shared by training and prediction.
  static Eigen::MatrixXf LogEnergies(const Eigen::MatrixXf& energies, double log_epsilon);

 private:
  MonoDepthFeatureParams features_;
  double log_epsilon_;
  DepthLabels labels_;
  int row_bands_;
  Eigen::VectorXf mean_, inv_std_, std_;
  Eigen::MatrixXf weights_;
};

}  // namespace aperture::perception
