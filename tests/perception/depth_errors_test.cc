// Ground truth per patch (median of the patch's millimetre depths, no surface = +inf) and Table I's
// E_ln / E_relative against analytic cases.
#include "perception/mono_depth/depth_errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace aperture::perception {
namespace {

PatchGrid SquareGrid(int rows, int cols, double patch_px) {
  PatchGrid grid;
  grid.rows = rows;
  grid.cols = cols;
  grid.frame_patch_px = Eigen::Vector2d::Constant(patch_px);
  return grid;
}

TEST(PatchDepthFromMillimetres, TakesTheMedianAndTreatsNoSurfaceAsFar) {
  const PatchGrid grid = SquareGrid(2, 3, 4.0);
  cv::Mat depth_mm(8, 12, CV_16U);
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 3; ++c) {
      depth_mm(cv::Rect(4 * c, 4 * r, 4, 4)).setTo(1000 * (1 + r * 3 + c));
    }
  }
  depth_mm.at<std::uint16_t>(0, 0) = 60000;  // one outlier: the median ignores it
  depth_mm(cv::Rect(8, 4, 4, 4)).setTo(0);   // patch (1, 2): sky
  depth_mm.at<std::uint16_t>(4, 8) = 2500;   // one surface pixel in the sky patch
  const cv::Mat truth = PatchDepthFromMillimetres(depth_mm, grid);
  ASSERT_EQ(truth.size(), cv::Size(3, 2));
  for (int i = 0; i < 5; ++i) EXPECT_FLOAT_EQ(truth.at<float>(i / 3, i % 3), 1.0f + i);
  EXPECT_TRUE(std::isinf(truth.at<float>(1, 2)));
}

TEST(PatchDepthFromMillimetres, RejectsAWrongTypeOrTooSmallImage) {
  EXPECT_THROW(PatchDepthFromMillimetres(cv::Mat(8, 12, CV_32F), SquareGrid(2, 3, 4.0)),
               std::invalid_argument);
  EXPECT_THROW(PatchDepthFromMillimetres(cv::Mat(8, 8, CV_16U), SquareGrid(2, 3, 4.0)),
               std::invalid_argument);
}

TEST(CompareDepth, MatchesTableIOnAnalyticCases) {
  cv::Mat truth =
      (cv::Mat_<float>(1, 4) << 2.0f, 4.0f, 8.0f, std::numeric_limits<float>::infinity());
  // Twice too far everywhere: E_ln = ln 2, E_relative = 1; the sky patch is not scored.
  const DepthErrors far = CompareDepth(truth * 2.0, truth, 0.5, 100.0);
  EXPECT_EQ(far.patches, 3);
  EXPECT_NEAR(far.MeanLn(), std::log(2.0), 1e-6);
  EXPECT_NEAR(far.MeanRelative(), 1.0, 1e-6);
  // Half as far: same E_ln, E_relative = 0.5.
  const DepthErrors near = CompareDepth(truth * 0.5, truth, 0.5, 100.0);
  EXPECT_NEAR(near.MeanLn(), std::log(2.0), 1e-6);
  EXPECT_NEAR(near.MeanRelative(), 0.5, 1e-6);
  // Clipping to [0.5, 5] m: 2 vs 4, 4 vs 5 (8 clipped) and 5 vs 5 (8 and 16 clipped).
  const DepthErrors clipped = CompareDepth(truth * 2.0, truth, 0.5, 5.0);
  EXPECT_NEAR(clipped.e_ln_sum, std::log(2.0) + std::log(5.0 / 4.0) + 0.0, 1e-6);
  DepthErrors sum = far;
  sum += near;
  EXPECT_EQ(sum.patches, 6);
  EXPECT_NEAR(sum.MeanRelative(), 0.75, 1e-6);
  EXPECT_TRUE(std::isnan(DepthErrors{}.MeanLn()));
  EXPECT_THROW(CompareDepth(truth, cv::Mat(1, 3, CV_32F), 0.5, 5.0), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
