#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>
#include <vector>

#include "perception/graph/frame_graph.h"
#include "perception/graph/serial_executor.h"
#include "perception/quality/image_quality_analyzer.h"
#include "perception/quality/image_quality_node.h"

namespace aperture::perception {
namespace {

cv::Mat Checkerboard(int size_px, int square_px) {
  cv::Mat image(size_px, size_px, CV_8UC1);
  for (int row = 0; row < size_px; ++row) {
    for (int col = 0; col < size_px; ++col) {
      image.at<uint8_t>(row, col) = ((row / square_px + col / square_px) % 2) ? 220 : 30;
    }
  }
  return image;
}

cv::Mat Blurred(const cv::Mat& image, double sigma_px) {
  cv::Mat blurred;
  cv::GaussianBlur(image, blurred, cv::Size(), sigma_px);
  return blurred;
}

TEST(ImageQualityAnalyzer, LaplacianVarianceDropsMonotonicallyWithBlur) {
  const cv::Mat board = Checkerboard(160, 10);
  ImageQualityAnalyzer analyzer;
  double previous = analyzer.Analyze(board).sharpness_laplacian_var;
  EXPECT_GT(previous, 0.0);
  // Gaussian blur multiplies the spectrum by exp(-sigma^2 w^2 / 2): every frequency loses energy as
  // sigma grows, so the Laplacian (weighting w^4) variance must fall strictly.
  for (double sigma_px : {0.5, 1.0, 1.5, 2.0, 3.0, 4.0}) {
    const double sharpness = analyzer.Analyze(Blurred(board, sigma_px)).sharpness_laplacian_var;
    EXPECT_LT(sharpness, previous) << "sigma " << sigma_px;
    previous = sharpness;
  }
}

TEST(ImageQualityAnalyzer, SharpnessOfASingleEdgeMatchesTheLaplacianByHand) {
  // Columns 0..9 at 0, 10..19 at 100: with the 4-neighbour Laplacian only columns 9 (+100) and
  // 10 (-100) are non-zero (reflect-101 borders keep the outer columns flat), so over 20 columns
  // the mean is 0 and the variance is (2 * 100^2) / 20 = 1000.
  cv::Mat edge(10, 20, CV_8UC1, cv::Scalar(0));
  edge.colRange(10, 20).setTo(100);
  ImageQualityAnalyzer analyzer;
  EXPECT_NEAR(analyzer.Analyze(edge).sharpness_laplacian_var, 1000.0, 1e-9);
}

TEST(ImageQualityAnalyzer, UniformImageHasZeroSharpnessAndItsOwnMean) {
  ImageQualityAnalyzer analyzer;
  const ImageQuality quality = analyzer.Analyze(cv::Mat(48, 64, CV_8UC1, cv::Scalar(100)));
  EXPECT_EQ(quality.sharpness_laplacian_var, 0.0);
  EXPECT_EQ(quality.mean_intensity, 100.0);
  EXPECT_EQ(quality.over_exposed_ratio, 0.0);
  EXPECT_EQ(quality.under_exposed_ratio, 0.0);
  // 100 * 16 / 256 = 6.25 -> bin 6 holds everything.
  ASSERT_EQ(quality.histogram.size(), 16u);
  EXPECT_EQ(quality.histogram[6], 1.0);
}

TEST(ImageQualityAnalyzer, ExposureRatiosEqualTheKnownFractions) {
  constexpr int kRows = 100;
  constexpr int kCols = 100;
  constexpr int kSaturated = 1234;     // set to 255
  constexpr int kAtOverLevel = 100;    // 250: counts as over-exposed
  constexpr int kBelowOverLevel = 77;  // 249: does not
  constexpr int kBlack = 567;          // 0
  constexpr int kAtUnderLevel = 50;    // 5: counts as under-exposed
  cv::Mat image(kRows, kCols, CV_8UC1, cv::Scalar(128));
  std::vector<int> pixels(kRows * kCols);
  std::iota(pixels.begin(), pixels.end(), 0);
  std::shuffle(pixels.begin(), pixels.end(), std::mt19937(7));
  auto next = pixels.begin();
  auto paint = [&](int count, uint8_t value) {
    for (int i = 0; i < count; ++i, ++next) image.at<uint8_t>(*next / kCols, *next % kCols) = value;
  };
  paint(kSaturated, 255);
  paint(kAtOverLevel, 250);
  paint(kBelowOverLevel, 249);
  paint(kBlack, 0);
  paint(kAtUnderLevel, 5);

  ImageQualityAnalyzer analyzer;
  const ImageQuality quality = analyzer.Analyze(image);
  const double n = kRows * kCols;
  EXPECT_DOUBLE_EQ(quality.over_exposed_ratio, (kSaturated + kAtOverLevel) / n);
  EXPECT_DOUBLE_EQ(quality.under_exposed_ratio, (kBlack + kAtUnderLevel) / n);
  EXPECT_NEAR(quality.mean_intensity, cv::mean(image)[0], 1e-9);
}

TEST(ImageQualityAnalyzer, HistogramIsNormalisedAndMatchesCounts) {
  cv::Mat image(120, 160, CV_8UC1);
  cv::randu(image, 0, 256);
  ImageQualityAnalyzer analyzer(ImageQualityParams{32});
  const ImageQuality quality = analyzer.Analyze(image);
  ASSERT_EQ(quality.histogram.size(), 32u);
  // Sum of 32 fractions of 19200 pixels: exact up to a few ulp.
  EXPECT_NEAR(std::accumulate(quality.histogram.begin(), quality.histogram.end(), 0.0), 1.0, 1e-12);
  // Bin 3 holds intensities 24..31.
  cv::Mat in_bin;
  cv::inRange(image, 24, 31, in_bin);
  EXPECT_DOUBLE_EQ(quality.histogram[3], cv::countNonZero(in_bin) / 19200.0);
}

TEST(ImageQualityAnalyzer, ColourInputIsConvertedToGray) {
  cv::Mat gray = Blurred(Checkerboard(64, 8), 1.0);
  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);  // equal channels: gray conversion is exact
  ImageQualityAnalyzer analyzer;
  const ImageQuality from_gray = analyzer.Analyze(gray);
  const ImageQuality from_bgr = analyzer.Analyze(bgr);
  EXPECT_EQ(from_bgr.histogram, from_gray.histogram);
  EXPECT_EQ(from_bgr.sharpness_laplacian_var, from_gray.sharpness_laplacian_var);
  EXPECT_EQ(from_bgr.mean_intensity, from_gray.mean_intensity);
}

TEST(ImageQualityAnalyzer, RejectsBadInputAndParams) {
  ImageQualityAnalyzer analyzer;
  EXPECT_THROW(analyzer.Analyze(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(analyzer.Analyze(cv::Mat(4, 4, CV_32FC1, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(ImageQualityAnalyzer(ImageQualityParams{0}), std::invalid_argument);
  EXPECT_THROW(ImageQualityAnalyzer(ImageQualityParams{16, 256, 5}), std::invalid_argument);
}

TEST(ImageQualityNode, EmitsTheAnalyzerResultsAsMetricsAndDrawsAnOverlay) {
  std::vector<std::unique_ptr<Node>> nodes;
  config::ParamReader params(YAML::Load("histogram_bins: 8"), "test.yaml");
  nodes.push_back(ImageQualityNode::Create(params, FrontEndResources{}));
  FrameGraph graph(std::move(nodes));
  SerialExecutor executor(graph);
  Frame frame;
  frame.image = Checkerboard(96, 12);
  const FrameSlots slots = executor.Run(frame);

  const ImageQuality expected = ImageQualityAnalyzer(ImageQualityParams{8}).Analyze(frame.image);
  const std::map<std::string, double> metrics = graph.CollectMetrics(slots);
  ASSERT_EQ(metrics.size(), 4u + 8u);
  EXPECT_EQ(metrics.at("image_quality.mean_intensity"), expected.mean_intensity);
  EXPECT_EQ(metrics.at("image_quality.sharpness_laplacian_var"), expected.sharpness_laplacian_var);
  EXPECT_EQ(metrics.at("image_quality.over_exposed_ratio"), expected.over_exposed_ratio);
  EXPECT_EQ(metrics.at("image_quality.under_exposed_ratio"), expected.under_exposed_ratio);
  EXPECT_EQ(metrics.at("image_quality.histogram_00"), expected.histogram[0]);
  EXPECT_EQ(metrics.at("image_quality.histogram_06"), expected.histogram[6]);

  const cv::Mat background(480, 640, CV_8UC3, cv::Scalar::all(128));
  cv::Mat overlay = background.clone();
  graph.DrawOverlays(slots, overlay);
  ASSERT_EQ(overlay.size(), background.size());
  const cv::Rect corner(0, 0, 320, 160);
  EXPECT_GT(cv::norm(overlay(corner), background(corner), cv::NORM_L1), 0.0);
  // Nothing drawn outside the top-left corner.
  const cv::Rect rest(320, 240, 320, 240);
  EXPECT_EQ(cv::norm(overlay(rest), background(rest), cv::NORM_L1), 0.0);
}

}  // namespace
}  // namespace aperture::perception
