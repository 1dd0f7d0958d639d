#include "perception/mono_depth/mono_depth_trainer.h"

#include <linear.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "perception/mono_depth/depth_errors.h"

namespace aperture::perception {
namespace {

// Score bias of labels absent from the training set: far below any trained score.
constexpr float kNeverScore = -1e6f;

void QuietLiblinear(const char*) {}

}  // namespace

void MonoDepthTrainParams::Validate() const {
  features.Validate();
  DepthLabels(min_depth_m, max_depth_m, labels);  // throws on a bad range or count
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("mono_depth training: " + what);
  };
  require(row_bands >= 0, "row_bands must be >= 0");
  require(log_epsilon > 0.0, "log_epsilon must be > 0");
  require(svm_c > 0.0, "svm_c must be > 0");
  require(svm_tolerance > 0.0, "svm_tolerance must be > 0");
  require(patch_stride >= 1, "patch_stride must be >= 1");
}

MonoDepthTrainer::MonoDepthTrainer(const MonoDepthTrainParams& params)
    : params_(params),
      extractor_(params.features),
      depth_labels_(params.min_depth_m, params.max_depth_m, params.labels) {
  params_.Validate();
}

void MonoDepthTrainer::AddFrame(const cv::Mat& bgr, const cv::Mat& depth_mm) {
  if (bgr.size() != depth_mm.size()) {
    throw std::invalid_argument(
        "mono_depth training: image and depth sizes differ; use the depth "
        "rendered with the image");
  }
  const PatchGrid grid = extractor_.Grid(bgr.size());
  const cv::Mat truth = PatchDepthFromMillimetres(depth_mm, grid);
  const Eigen::MatrixXf logs =
      MonoDepthModel::LogEnergies(extractor_.Extract(bgr), params_.log_epsilon);
  for (int i = 0; i < logs.rows(); i += params_.patch_stride) {
    const int r = i / grid.cols, c = i % grid.cols;
    log_energies_.push_back(logs.row(i).transpose());
    bands_.push_back(r * params_.row_bands / grid.rows);
    labels_.push_back(depth_labels_.LabelOf(truth.at<float>(r, c)));
  }
  ++frames_;
}

MonoDepthModel MonoDepthTrainer::Train(MonoDepthTrainingReport* report) const {
  const std::size_t n = labels_.size();
  if (n == 0) throw std::invalid_argument("mono_depth training: no training patches");
  // Standardisation over the training set.
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(MonoDepthFeatureExtractor::kFeatures),
                  sq = Eigen::VectorXd::Zero(MonoDepthFeatureExtractor::kFeatures);
  for (const Eigen::VectorXf& x : log_energies_) {
    mean += x.cast<double>();
    sq += x.cast<double>().cwiseAbs2();
  }
  mean /= double(n);
  Eigen::VectorXd std_dev = (sq / double(n) - mean.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
  std_dev = std_dev.cwiseMax(1e-6);  // a constant feature carries nothing; keep it harmless

  // liblinear problem: dense rows, 1-based indices, row band one-hot, explicit bias input.
  const int inputs = MonoDepthFeatureExtractor::kFeatures + params_.row_bands + 1;
  const int nodes_per_row = MonoDepthFeatureExtractor::kFeatures + (params_.row_bands > 0 ? 1 : 0) +
                            1 + 1;  // + terminator
  std::vector<feature_node> nodes(n * nodes_per_row);
  std::vector<feature_node*> rows(n);
  std::vector<double> y(n);
  std::vector<std::size_t> per_label(depth_labels_.Count(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    feature_node* node = &nodes[i * nodes_per_row];
    rows[i] = node;
    for (int j = 0; j < MonoDepthFeatureExtractor::kFeatures; ++j) {
      *node++ = {j + 1, (log_energies_[i][j] - mean[j]) / std_dev[j]};
    }
    if (params_.row_bands > 0)
      *node++ = {MonoDepthFeatureExtractor::kFeatures + bands_[i] + 1, 1.0};
    *node++ = {inputs, 1.0};  // bias
    *node = {-1, 0.0};
    y[i] = labels_[i];
    ++per_label[labels_[i]];
  }
  int present = 0;
  for (std::size_t count : per_label) present += count > 0 ? 1 : 0;
  if (present < 2) {
    throw std::invalid_argument(
        "mono_depth training: the ground truth covers fewer than two "
        "depth labels; add frames with near and far surfaces");
  }
  problem prob{};
  prob.l = static_cast<int>(n);
  prob.n = inputs;
  prob.y = y.data();
  prob.x = rows.data();
  prob.bias = -1.0;  // the bias is the explicit last input
  parameter param{};
  param.solver_type = L2R_L2LOSS_SVC;
  param.eps = params_.svm_tolerance;
  param.C = params_.svm_c;
  if (const char* error = check_parameter(&prob, &param)) {
    throw std::invalid_argument(std::string("mono_depth training: liblinear: ") + error);
  }
  set_print_string_function(&QuietLiblinear);
  const auto start = std::chrono::steady_clock::now();
  model* svm = train(&prob, &param);
  const double train_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  Eigen::MatrixXf weights = Eigen::MatrixXf::Zero(depth_labels_.Count(), inputs);
  weights.col(inputs - 1).setConstant(kNeverScore);
  for (int k = 0; k < svm->nr_class; ++k) {
    const int label = svm->label[k];
    for (int j = 0; j < inputs; ++j) weights(label, j) = float(get_decfun_coef(svm, j + 1, k));
  }
  free_and_destroy_model(&svm);

  MonoDepthModel model(params_.features, params_.log_epsilon, depth_labels_, params_.row_bands,
                       mean.cast<float>(), std_dev.cast<float>(), weights);
  if (report) {
    report->frames = frames_;
    report->patches = n;
    report->patches_per_label = per_label;
    report->train_time_s = train_time_s;
    std::size_t correct = 0;
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::VectorXf input = Eigen::VectorXf::Zero(inputs);
      input.head(MonoDepthFeatureExtractor::kFeatures) =
          ((log_energies_[i].cast<double>() - mean).cwiseQuotient(std_dev)).cast<float>();
      if (params_.row_bands > 0) input[MonoDepthFeatureExtractor::kFeatures + bands_[i]] = 1.0f;
      input[inputs - 1] = 1.0f;
      Eigen::Index best = 0;
      (weights * input).maxCoeff(&best);
      correct += best == labels_[i] ? 1 : 0;
    }
    report->training_accuracy = double(correct) / double(n);
  }
  return model;
}

}  // namespace aperture::perception
