#include "perception/mono_depth/mono_depth_model.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace aperture::perception {
namespace {

// Reads the non-comment lines of a model file, naming file and line in every error.
class ModelReader {
 public:
  ModelReader(std::istream& in, std::string source) : in_(in), source_(std::move(source)) {}

  // The next non-empty, non-comment line, which must start with `keyword`.
  std::istringstream Line(const std::string& keyword) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      if (line.empty() || line[0] == '#') continue;
      std::istringstream fields(line);
      std::string first;
      fields >> first;
      if (!keyword.empty() && first != keyword)
        Fail("expected '" + keyword + "', found '" + first + "'");
      if (keyword.empty()) fields.seekg(0);
      return fields;
    }
    Fail("file ends before '" + (keyword.empty() ? std::string("weights row") : keyword) + "'");
  }

  template <typename T>
  T Number(std::istringstream& fields, const std::string& what) {
    T value{};
    if (!(fields >> value)) Fail("expected " + what);
    return value;
  }

  Eigen::VectorXf Vector(std::istringstream& fields, int size, const std::string& what) {
    Eigen::VectorXf v(size);
    for (int i = 0; i < size; ++i)
      v[i] = Number<float>(fields, what + " value " + std::to_string(i));
    std::string extra;
    if (fields >> extra) Fail("more than " + std::to_string(size) + " values for " + what);
    return v;
  }

  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument("mono_depth model '" + source_ + "' line " +
                                std::to_string(line_number_) + ": " + what +
                                " (retrain with `aperture train mono_depth`)");
  }

 private:
  std::istream& in_;
  std::string source_;
  int line_number_ = 0;
};

}  // namespace

MonoDepthModel::MonoDepthModel(const MonoDepthFeatureParams& features, double log_epsilon,
                               DepthLabels labels, int row_bands, Eigen::VectorXf mean,
                               Eigen::VectorXf std_dev, Eigen::MatrixXf weights)
    : features_(features),
      log_epsilon_(log_epsilon),
      labels_(std::move(labels)),
      row_bands_(row_bands),
      mean_(std::move(mean)),
      std_(std::move(std_dev)),
      weights_(std::move(weights)) {
  features_.Validate();
  if (!(log_epsilon_ > 0.0) || row_bands_ < 0 ||
      mean_.size() != MonoDepthFeatureExtractor::kFeatures ||
      std_.size() != MonoDepthFeatureExtractor::kFeatures || weights_.rows() != labels_.Count() ||
      weights_.cols() != MonoDepthFeatureExtractor::kFeatures + row_bands_ + 1) {
    throw std::invalid_argument(
        "mono_depth model: inconsistent sizes (need log_epsilon > 0, row_bands >= 0, 102 means "
        "and stds, weights labels x (102 + row_bands + 1))");
  }
  if (!(std_.array() > 0.0f).all() || !mean_.allFinite() || !weights_.allFinite()) {
    throw std::invalid_argument("mono_depth model: non-positive std or non-finite numbers");
  }
  inv_std_ = std_.cwiseInverse();
}

MonoDepthModel MonoDepthModel::Load(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::invalid_argument("mono_depth model: cannot read '" + path +
                                "' (give an existing file written by `aperture train mono_depth`)");
  }
  return Parse(in, path);
}

MonoDepthModel MonoDepthModel::Parse(std::istream& in, const std::string& source) {
  ModelReader reader(in, source);
  std::istringstream header = reader.Line(kMagic);
  const int version = reader.Number<int>(header, "a version number");
  if (version != kVersion) {
    reader.Fail("version " + std::to_string(version) + ", this build reads version " +
                std::to_string(kVersion));
  }
  std::istringstream features_line = reader.Line("features");
  MonoDepthFeatureParams features;
  features.work_width_px = reader.Number<int>(features_line, "work_width_px");
  features.patch_px = reader.Number<int>(features_line, "patch_px");
  features.scale_factor = reader.Number<int>(features_line, "scale_factor");
  const double log_epsilon = reader.Number<double>(features_line, "log_epsilon");
  std::istringstream labels_line = reader.Line("labels");
  const int count = reader.Number<int>(labels_line, "the label count");
  if (count < 2 || count > 1000) reader.Fail("label count " + std::to_string(count));
  const Eigen::VectorXf edges = reader.Vector(labels_line, count + 1, "label edges");
  std::istringstream bands_line = reader.Line("row_bands");
  const int row_bands = reader.Number<int>(bands_line, "row_bands");
  if (row_bands < 0 || row_bands > 10000) reader.Fail("row_bands " + std::to_string(row_bands));
  std::istringstream mean_line = reader.Line("mean");
  const Eigen::VectorXf mean =
      reader.Vector(mean_line, MonoDepthFeatureExtractor::kFeatures, "mean");
  std::istringstream std_line = reader.Line("std");
  const Eigen::VectorXf std_dev =
      reader.Vector(std_line, MonoDepthFeatureExtractor::kFeatures, "std");
  std::istringstream weights_line = reader.Line("weights");
  const int rows = reader.Number<int>(weights_line, "weight rows");
  const int cols = reader.Number<int>(weights_line, "weight columns");
  if (rows != count || cols != MonoDepthFeatureExtractor::kFeatures + row_bands + 1) {
    reader.Fail("weights " + std::to_string(rows) + " x " + std::to_string(cols) + ", expected " +
                std::to_string(count) + " x " +
                std::to_string(MonoDepthFeatureExtractor::kFeatures + row_bands + 1));
  }
  Eigen::MatrixXf weights(rows, cols);
  for (int i = 0; i < rows; ++i) {
    std::istringstream row = reader.Line("");
    weights.row(i) = reader.Vector(row, cols, "weights row " + std::to_string(i)).transpose();
  }
  try {
    DepthLabels labels(edges[0], edges[count], count);
    for (int i = 0; i <= count; ++i) {
      if (std::abs(labels.Edges()[i] - edges[i]) > 1e-3 * edges[i]) {
        reader.Fail("label edges are not geometric between " + std::to_string(edges[0]) + " and " +
                    std::to_string(edges[count]) + " m");
      }
    }
    return MonoDepthModel(features, log_epsilon, labels, row_bands, mean, std_dev, weights);
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).rfind("mono_depth model '", 0) == 0) throw;
    reader.Fail(e.what());
  }
}

void MonoDepthModel::Save(const std::string& path) const {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("mono_depth model: cannot write '" + path + "'");
  Write(out);
  if (!out) throw std::runtime_error("mono_depth model: writing '" + path + "' failed");
}

void MonoDepthModel::Write(std::ostream& out) const {
  out << kMagic << ' ' << kVersion << '\n'
      << "# seed 003 Sec. III-A per-patch linear SVM; see "
         "perception/mono_depth/mono_depth_model.h\n"
      << std::setprecision(9) << "features " << features_.work_width_px << ' ' << features_.patch_px
      << ' ' << features_.scale_factor << ' ' << log_epsilon_ << '\n'
      << "labels " << labels_.Count();
  for (double edge : labels_.Edges()) out << ' ' << edge;
  out << "\nrow_bands " << row_bands_ << "\nmean";
  for (int i = 0; i < mean_.size(); ++i) out << ' ' << mean_[i];
  out << "\nstd";
  for (int i = 0; i < std_.size(); ++i) out << ' ' << std_[i];
  out << "\nweights " << weights_.rows() << ' ' << weights_.cols() << '\n';
  for (int r = 0; r < weights_.rows(); ++r) {
    for (int c = 0; c < weights_.cols(); ++c) out << (c ? " " : "") << weights_(r, c);
    out << '\n';
  }
}

Eigen::MatrixXf MonoDepthModel::LogEnergies(const Eigen::MatrixXf& energies, double log_epsilon) {
  return (energies.array() + float(log_epsilon)).log().matrix();
}

Eigen::MatrixXf MonoDepthModel::Inputs(const Eigen::MatrixXf& energies,
                                       const PatchGrid& grid) const {
  if (energies.cols() != MonoDepthFeatureExtractor::kFeatures ||
      energies.rows() != grid.rows * grid.cols) {
    throw std::invalid_argument("mono_depth model: energies must be (grid rows * cols) x 102");
  }
  Eigen::MatrixXf inputs = Eigen::MatrixXf::Zero(energies.rows(), InputSize());
  inputs.leftCols(MonoDepthFeatureExtractor::kFeatures) =
      ((LogEnergies(energies, log_epsilon_).rowwise() - mean_.transpose()).array().rowwise() *
       inv_std_.transpose().array())
          .matrix();
  for (int r = 0; r < grid.rows; ++r) {
    const int band = r * row_bands_ / grid.rows;
    for (int c = 0; c < grid.cols; ++c) {
      if (row_bands_ > 0)
        inputs(r * grid.cols + c, MonoDepthFeatureExtractor::kFeatures + band) = 1.0f;
    }
  }
  inputs.col(InputSize() - 1).setOnes();
  return inputs;
}

cv::Mat MonoDepthModel::PredictLabels(const Eigen::MatrixXf& energies,
                                      const PatchGrid& grid) const {
  const Eigen::MatrixXf scores = Inputs(energies, grid) * weights_.transpose();
  cv::Mat labels(grid.rows, grid.cols, CV_32S);
  for (int i = 0; i < scores.rows(); ++i) {
    Eigen::Index best = 0;
    scores.row(i).maxCoeff(&best);
    labels.at<int>(i / grid.cols, i % grid.cols) = static_cast<int>(best);
  }
  return labels;
}

cv::Mat MonoDepthModel::PredictDepth(const Eigen::MatrixXf& energies, const PatchGrid& grid) const {
  const cv::Mat labels = PredictLabels(energies, grid);
  cv::Mat depth(labels.size(), CV_32F);
  for (int r = 0; r < labels.rows; ++r) {
    for (int c = 0; c < labels.cols; ++c) {
      depth.at<float>(r, c) = float(labels_.DepthOf(labels.at<int>(r, c)));
    }
  }
  return depth;
}

}  // namespace aperture::perception
