// The flow-mode statistics of TS²P's segmentation (perception/ts2p/ts2p_detector.h) on values
// drawn from known distributions, and the checks of the segmentation's parameters.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <random>

#include "perception/ts2p/ts2p_detector.h"
#include "tests/support/message_of.h"

namespace aperture::perception {
namespace {

// A wall's parallax N(wall_px, sigma) over the image and a fraction `opening` of pixels at
// opening_px; a NaN band (pixels without parallax) that the statistics must skip.
cv::Mat WallAndOpening(double wall_px, double sigma, double opening, double opening_px) {
  std::mt19937 rng(7);
  std::normal_distribution<float> wall(static_cast<float>(wall_px), static_cast<float>(sigma));
  cv::Mat values(240, 320, CV_32FC1);
  const int opening_pixels = static_cast<int>(opening * values.total());
  for (int i = 0; i < static_cast<int>(values.total()); ++i) {
    values.at<float>(i / values.cols, i % values.cols) =
        i < opening_pixels ? static_cast<float>(opening_px) : wall(rng);
  }
  values.row(values.rows - 1).setTo(std::numeric_limits<float>::quiet_NaN());
  return values;
}

TEST(Ts2pModesTest, TwoMeansSplitsTheWallWhenTheOpeningIsSmall) {
  // 2 % of the pixels 1.4 px below a wall of spread 0.3 px: the split that reduces the variance
  // most cuts the wall in two (what made small openings undetectable), ...
  const cv::Mat values = WallAndOpening(4.4, 0.3, 0.02, 3.0);
  double low = 0.0, high = 0.0;
  TwoMeansThreshold(values, &low, &high);
  EXPECT_GT(low, 3.8);
  // ... while the low tail finds the opening's own mode and the wall's.
  const std::optional<LowTailMode> tail = FindLowTailMode(values, 0.005);
  ASSERT_TRUE(tail.has_value());
  EXPECT_NEAR(tail->low, 3.0, 1e-6);
  EXPECT_NEAR(tail->high, 4.4, 0.02);
  // The cutoff is 4 robust spreads below the wall's median: between the modes.
  EXPECT_NEAR(tail->cutoff, 4.4 - 4.0 * 0.3, 0.05);
}

TEST(Ts2pModesTest, NoTailWithoutASecondMode) {
  // A normal wall alone: its own tail beyond 4 spreads holds ~0.003 % of the pixels.
  EXPECT_FALSE(FindLowTailMode(WallAndOpening(4.4, 0.3, 0.0, 0.0), 0.005).has_value());
  // A second mode smaller than min_fraction is speckle, not an opening.
  EXPECT_FALSE(FindLowTailMode(WallAndOpening(4.4, 0.3, 0.003, 2.0), 0.005).has_value());
  EXPECT_TRUE(FindLowTailMode(WallAndOpening(4.4, 0.3, 0.008, 2.0), 0.005).has_value());
  // All NaN: nothing to find.
  cv::Mat nan(8, 8, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_FALSE(FindLowTailMode(nan, 0.005).has_value());
}

// The hysteresis core's fraction must lie below the detection's own (else the core is O).
TEST(Ts2pParamsTest, CoreThresholdBelowTheDetectionThreshold) {
  Ts2pParams params;
  params.core_threshold_fraction = 0.6;
  EXPECT_NO_THROW(params.Validate());
  params.core_threshold_fraction = params.threshold_fraction;
  EXPECT_THAT(test_support::MessageOf([&] { params.Validate(); }),
              ::testing::HasSubstr("ts2p.core_threshold_fraction"));
  params.core_threshold_fraction = 0.6;
  params.min_core_fraction = 0.0;
  EXPECT_THAT(test_support::MessageOf([&] { params.Validate(); }),
              ::testing::HasSubstr("min_core_fraction"));
}

}  // namespace
}  // namespace aperture::perception
