// DepthLabels: geometric bins (equal width in ln depth, growing in metres), centres map back to
// their own label, out-of-range and invalid depths go to the ends, bad ranges are rejected.
#include "perception/mono_depth/depth_labels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace aperture::perception {
namespace {

TEST(DepthLabels, BinsHaveEqualLnWidthAndGrowInMetres) {
  const DepthLabels labels(0.5, 40.0, 16);
  ASSERT_EQ(labels.Count(), 16);
  const double ln_width = std::log(40.0 / 0.5) / 16;
  for (int i = 0; i < labels.Count(); ++i) {
    EXPECT_NEAR(std::log(labels.Edges()[i + 1] / labels.Edges()[i]), ln_width, 1e-12);
    if (i > 0) {
      EXPECT_GT(labels.Edges()[i + 1] - labels.Edges()[i],
                labels.Edges()[i] - labels.Edges()[i - 1]);
    }
    // The centre is the geometric mean and maps back to its own label.
    EXPECT_NEAR(labels.DepthOf(i), std::sqrt(labels.Edges()[i] * labels.Edges()[i + 1]), 1e-12);
    EXPECT_EQ(labels.LabelOf(labels.DepthOf(i)), i);
  }
}

TEST(DepthLabels, OutOfRangeAndInvalidDepthsGoToTheEnds) {
  const DepthLabels labels(1.0, 81.0, 4);  // edges 1, 3, 9, 27, 81
  EXPECT_EQ(labels.LabelOf(0.2), 0);
  EXPECT_EQ(labels.LabelOf(2.99), 0);
  EXPECT_EQ(labels.LabelOf(3.01), 1);
  EXPECT_EQ(labels.LabelOf(80.0), 3);
  EXPECT_EQ(labels.LabelOf(500.0), 3);
  EXPECT_EQ(labels.LabelOf(std::numeric_limits<double>::infinity()), 3);
  EXPECT_EQ(labels.LabelOf(std::numeric_limits<double>::quiet_NaN()), 3);
  EXPECT_NEAR(labels.DepthOf(1), std::sqrt(27.0), 1e-12);
  EXPECT_THROW(labels.DepthOf(4), std::out_of_range);
}

TEST(DepthLabels, RejectsBadRanges) {
  EXPECT_THROW(DepthLabels(0.0, 10.0, 4), std::invalid_argument);
  EXPECT_THROW(DepthLabels(5.0, 5.0, 4), std::invalid_argument);
  EXPECT_THROW(DepthLabels(1.0, std::numeric_limits<double>::infinity(), 4), std::invalid_argument);
  EXPECT_THROW(DepthLabels(1.0, 10.0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
