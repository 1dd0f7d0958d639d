// MonoDepthModel: the text format round-trips exactly (same predictions), the classifier picks
// the label of the largest score with the row-band inputs in the right place, and malformed files
// are rejected with the file, the line and what was wrong. The shipped model loads.
#include "perception/mono_depth/mono_depth_model.h"

#include <gtest/gtest.h>

#include <sstream>

#include "perception/mono_depth/mono_depth_estimator.h"

namespace aperture::perception {
namespace {

constexpr int kEnergies = MonoDepthFeatureExtractor::kFeatures;

// A model whose label is decided by the row band alone: band b votes for label 2 b + 1.
MonoDepthModel RowBandModel() {
  const DepthLabels labels(1.0, 64.0, 6);
  const int bands = 3;
  Eigen::MatrixXf weights = Eigen::MatrixXf::Zero(6, kEnergies + bands + 1);
  for (int b = 0; b < bands; ++b) weights(2 * b + 1, kEnergies + b) = 1.0f;
  weights(0, 5) = 1e-3f;  // a small energy weight: a round trip must keep it
  return MonoDepthModel(MonoDepthFeatureParams{}, 1e-3, labels, bands,
                        Eigen::VectorXf::LinSpaced(kEnergies, 0.0f, 1.0f),
                        Eigen::VectorXf::Constant(kEnergies, 2.0f), weights);
}

PatchGrid ExtractorGrid(int rows, int cols) {
  PatchGrid grid;
  grid.rows = rows;
  grid.cols = cols;
  grid.frame_patch_px = Eigen::Vector2d::Constant(8.0);
  return grid;
}

TEST(MonoDepthModel, PredictsTheLabelOfTheLargestScore) {
  const MonoDepthModel model = RowBandModel();
  const PatchGrid grid = ExtractorGrid(6, 2);
  const Eigen::MatrixXf energies = Eigen::MatrixXf::Ones(12, kEnergies);
  const cv::Mat labels = model.PredictLabels(energies, grid);
  const cv::Mat depth = model.PredictDepth(energies, grid);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 2; ++c) {
      EXPECT_EQ(labels.at<int>(r, c), 2 * (r / 2) + 1) << r;  // 6 rows in 3 bands
      EXPECT_FLOAT_EQ(depth.at<float>(r, c), float(model.labels().DepthOf(2 * (r / 2) + 1)));
    }
  }
  // Standardised inputs: (ln(eps + E) - mean) / std, then the band one-hot and the bias.
  const Eigen::MatrixXf inputs = model.Inputs(energies, grid);
  EXPECT_NEAR(inputs(0, 0), (std::log(1.0 + 1e-3) - 0.0) / 2.0, 1e-6);
  EXPECT_FLOAT_EQ(inputs(11, kEnergies + 2), 1.0f);
  EXPECT_FLOAT_EQ(inputs(11, kEnergies + 0), 0.0f);
  EXPECT_FLOAT_EQ(inputs(11, model.InputSize() - 1), 1.0f);
  EXPECT_THROW(model.PredictLabels(Eigen::MatrixXf::Ones(11, kEnergies), grid),
               std::invalid_argument);
}

TEST(MonoDepthModel, TextFormatRoundTrips) {
  const MonoDepthModel model = RowBandModel();
  std::stringstream text;
  model.Write(text);
  const MonoDepthModel loaded = MonoDepthModel::Parse(text, "round trip");
  EXPECT_EQ(loaded.row_bands(), 3);
  EXPECT_EQ(loaded.labels().Count(), 6);
  EXPECT_TRUE(loaded.weights().isApprox(model.weights(), 1e-7f));
  const Eigen::MatrixXf energies = Eigen::MatrixXf::Random(12, kEnergies).cwiseAbs();
  EXPECT_TRUE(loaded.Inputs(energies, ExtractorGrid(6, 2))
                  .isApprox(model.Inputs(energies, ExtractorGrid(6, 2)), 1e-6f));
}

std::string ParseError(const std::string& text) {
  std::istringstream in(text);
  try {
    MonoDepthModel::Parse(in, "bad.model");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(MonoDepthModel, RejectsMalformedFilesNamingTheLine) {
  std::stringstream good;
  RowBandModel().Write(good);
  const std::string text = good.str();
  std::string other_version = text;
  other_version.replace(text.find(" 1\n"), 3, " 7\n");
  EXPECT_NE(ParseError(other_version).find("version 7"), std::string::npos);
  EXPECT_NE(ParseError("not a model\n").find("bad.model' line 1"), std::string::npos);
  const std::string truncated = text.substr(0, text.rfind('\n', text.size() - 2) + 1);
  EXPECT_NE(ParseError(truncated).find("file ends"), std::string::npos) << ParseError(truncated);
  std::string wrong_count = text;
  wrong_count.replace(wrong_count.find("weights 6 106"), 13, "weights 6 105");
  EXPECT_NE(ParseError(wrong_count).find("expected 6 x 106"), std::string::npos);
  EXPECT_THROW(MonoDepthModel::Load("/nonexistent/dir/forest.model"), std::invalid_argument);
}

TEST(MonoDepthModel, ShippedModelLoads) {
  const MonoDepthModel model = DefaultMonoDepthModel();
  EXPECT_EQ(model.InputSize(), kEnergies + model.row_bands() + 1);
  EXPECT_GE(model.labels().Count(), 2);
}

}  // namespace
}  // namespace aperture::perception
