#include "planning/fast_acos.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace aperture::planning {
namespace {

// Dense sweep of [-1, 1] (step 2e-6, both branches and the switch at |x| = 0.5) and the points
// near +-1 where acos is steepest, against long-double acos rounded to double. Tolerance 6e-16 rad:
// the header promises 1 ulp of pi (4.4e-16); anything above means a wrong coefficient or branch.
TEST(FastAcos, MatchesLongDoubleAcosToOneUlpOfPi) {
  double max_error = 0.0;
  const auto check = [&](double x) {
    const double expected = static_cast<double>(std::acos(static_cast<long double>(x)));
    max_error = std::max(max_error, std::abs(FastAcos(x) - expected));
  };
  constexpr int kSteps = 1000000;
  for (int i = 0; i <= kSteps; ++i) check(-1.0 + 2.0 * i / kSteps);
  for (double e = 1e-18; e < 1e-3; e *= 1.7) {
    check(1.0 - e);
    check(-1.0 + e);
    check(0.5 + e);
    check(0.5 - e);
  }
  EXPECT_LT(max_error, 6e-16);
  EXPECT_EQ(FastAcos(1.0), 0.0);
  EXPECT_DOUBLE_EQ(FastAcos(-1.0), std::acos(-1.0));
  EXPECT_DOUBLE_EQ(FastAcos(0.0), std::acos(0.0));
}

TEST(FastAcos, ClampsOutOfRangeArgumentsAndPropagatesNan) {
  EXPECT_EQ(FastAcos(1.0 + 1e-12), 0.0);
  EXPECT_DOUBLE_EQ(FastAcos(-1.0 - 1e-12), std::acos(-1.0));
  EXPECT_TRUE(std::isnan(FastAcos(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace
}  // namespace aperture::planning
