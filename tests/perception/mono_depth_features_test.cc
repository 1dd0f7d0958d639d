// MonoDepthFeatureExtractor against analytic responses: on an intensity ramp I = a x the x
// derivative filters give a exactly, the edge filter at angle theta gives a cos(theta), the level
// average gives the intensity, squared energies are the squares, and each coarser scale sees the
// ramp scale_factor times steeper; the colour channels give the haze averages.
#include "perception/mono_depth/mono_depth_features.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace aperture::perception {
namespace {

constexpr int kPerScale = MonoDepthFeatureExtractor::kFeaturesPerScale;
constexpr int kFilters = MonoDepthFeatureExtractor::kFilters;

// Column of filter n (0-based: 0-8 Laws, 9 Cr, 10 Cb, 11-16 edges), energy power k, scale s.
int Column(int scale, int k, int filter) { return scale * kPerScale + (k - 1) * kFilters + filter; }

// A gray horizontal ramp I(x) = slope * x at the work resolution (no resize).
cv::Mat Ramp(int width, int height, double slope) {
  cv::Mat gray(height, width, CV_8U);
  for (int x = 0; x < width; ++x) gray.col(x).setTo(std::lround(slope * x));
  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

TEST(MonoDepthFeatureExtractor, GridCoversTheFrameInPatches) {
  MonoDepthFeatureExtractor extractor;  // 320 px work width, 8 px patches
  const PatchGrid grid = extractor.Grid(cv::Size(640, 480));
  EXPECT_EQ(grid.cols, 40);
  EXPECT_EQ(grid.rows, 30);
  EXPECT_DOUBLE_EQ(grid.frame_patch_px.x(), 16.0);
  const Eigen::MatrixXf features = extractor.Extract(Ramp(640, 480, 0.25));
  EXPECT_EQ(features.rows(), 40 * 30);
  EXPECT_EQ(features.cols(), 102);
  EXPECT_TRUE(features.allFinite());
}

TEST(MonoDepthFeatureExtractor, RampGivesAnalyticEnergiesAtEveryScale) {
  MonoDepthFeatureParams params;
  params.work_width_px = 360;  // 360 / 9 = 40: the two coarser levels downsample exactly
  params.patch_px = 8;
  MonoDepthFeatureExtractor extractor(params);
  const double slope = 0.5;  // gray levels per pixel; the ramp spans 0..180 (8-bit quantised)
  const cv::Mat bgr = Ramp(360, 270, slope);
  const PatchGrid grid = extractor.Grid(bgr.size());
  const Eigen::MatrixXf features = extractor.Extract(bgr);
  // A patch in the middle, away from the borders at every scale (windows of 8, 24, 72 px).
  const int r = grid.rows / 2, c = grid.cols / 2, patch = r * grid.cols + c;
  // Quantisation of the 8-bit ramp (0.5 per px rounds to steps) averages out over a patch; the
  // tolerance covers the residual of rounding at window edges.
  for (int s = 0; s < 3; ++s) {
    const double a = slope * std::pow(3.0, s);  // the ramp at level s
    // Laws E3 along x (with L3 along y) = d/dx; E3 along y = 0.
    EXPECT_NEAR(features(patch, Column(s, 1, 1)), a, 0.05 * a) << "scale " << s;
    EXPECT_NEAR(features(patch, Column(s, 1, 3)), 0.0, 1e-3) << "scale " << s;
    // Oriented edges: |a cos(theta)|, theta = 0, 30, ..., 150 deg; squared: (a cos theta)^2.
    for (int o = 0; o < 6; ++o) {
      const double expected = std::abs(a * std::cos(o * M_PI / 6.0));
      EXPECT_NEAR(features(patch, Column(s, 1, 11 + o)), expected, 0.05 * a + 1e-3)
          << "scale " << s << " orientation " << 30 * o;
      EXPECT_NEAR(features(patch, Column(s, 2, 11 + o)), expected * expected, 0.1 * a * a + 1e-3)
          << "scale " << s << " orientation " << 30 * o;
    }
    // Level average (L3 L3) = the intensity at the patch centre column; gray has Cr = Cb = 128.
    const double centre_x = (c + 0.5) * params.patch_px;
    EXPECT_NEAR(features(patch, Column(s, 1, 0)), slope * centre_x, 1.0) << "scale " << s;
    EXPECT_NEAR(features(patch, Column(s, 1, 9)), 128.0, 0.5);
    EXPECT_NEAR(features(patch, Column(s, 1, 10)), 128.0, 0.5);
  }
}

TEST(MonoDepthFeatureExtractor, ColourChannelsCarryTheHazeCue) {
  MonoDepthFeatureExtractor extractor;
  cv::Mat blue(240, 320, CV_8UC3, cv::Scalar(200, 120, 90));  // BGR: bluish haze
  cv::Mat red(240, 320, CV_8UC3, cv::Scalar(90, 120, 200));
  const Eigen::MatrixXf f_blue = extractor.Extract(blue);
  const Eigen::MatrixXf f_red = extractor.Extract(red);
  // Cb (filter 10) above 128 for blue, Cr (filter 9) above 128 for red; texture energies zero.
  EXPECT_GT(f_blue(0, Column(0, 1, 10)), 140.0f);
  EXPECT_LT(f_blue(0, Column(0, 1, 9)), 128.0f);
  EXPECT_GT(f_red(0, Column(0, 1, 9)), 140.0f);
  for (int n = 1; n < 9; ++n) EXPECT_NEAR(f_blue(100, Column(0, 1, n)), 0.0f, 1e-4f);
}

TEST(MonoDepthFeatureExtractor, RejectsGrayEmptyAndTinyImages) {
  MonoDepthFeatureExtractor extractor;
  try {
    extractor.Extract(cv::Mat(240, 320, CV_8UC1, cv::Scalar(7)));
    FAIL() << "gray image accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--color"), std::string::npos) << e.what();
  }
  EXPECT_THROW(extractor.Extract(cv::Mat()), std::invalid_argument);
  EXPECT_THROW(extractor.Extract(cv::Mat(2, 640, CV_8UC3)), std::invalid_argument);
  MonoDepthFeatureParams bad;
  bad.patch_px = 1;
  EXPECT_THROW(MonoDepthFeatureExtractor{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
