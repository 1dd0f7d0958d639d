#include "control/require.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "control/constants.h"

namespace aperture::control {
namespace {

using ::testing::HasSubstr;

template <typename F>
std::string MessageOf(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(RequireTest, MessagesNameTheValueAndTheRule) {
  EXPECT_EQ(MessageOf([] { RequirePositive(-1.5, "GapMissionParams.hover_s"); }),
            "GapMissionParams.hover_s = -1.5 must be finite and > 0");
  EXPECT_EQ(MessageOf([] { RequireNonNegative(-2e-7, "A.b"); }),
            "A.b = -2e-07 must be finite and >= 0");
  EXPECT_EQ(MessageOf([] { RequireAtLeast(0, 1, "A.count"); }), "A.count = 0 must be >= 1");
  EXPECT_EQ(MessageOf([] { RequireInRange(1.5, 0.0, 1.0, "A.p"); }), "A.p = 1.5 must be in [0, 1]");
  EXPECT_EQ(MessageOf([] { Require(false, "A.x", 3.0, "must be even"); }), "A.x = 3 must be even");
  EXPECT_EQ(MessageOf([] { Require(false, "A.mode", "must name a mode"); }),
            "A.mode must name a mode");
  EXPECT_THAT(MessageOf([] { RequireFinite(Eigen::Vector3d(0.0, kNaN, 1.0), "A.p_W"); }),
              HasSubstr("A.p_W must be finite"));
}

TEST(RequireTest, BoundariesAndNonFiniteValues) {
  EXPECT_NO_THROW(RequirePositive(1e-300, "v"));
  EXPECT_THROW(RequirePositive(0.0, "v"), std::invalid_argument);
  EXPECT_THROW(RequirePositive(kInf, "v"), std::invalid_argument);
  EXPECT_THROW(RequirePositive(kNaN, "v"), std::invalid_argument);
  EXPECT_NO_THROW(RequireNonNegative(0.0, "v"));
  EXPECT_THROW(RequireNonNegative(-1e-300, "v"), std::invalid_argument);
  EXPECT_THROW(RequireNonNegative(kNaN, "v"), std::invalid_argument);
  EXPECT_NO_THROW(RequireFinite(-1e300, "v"));
  EXPECT_THROW(RequireFinite(-kInf, "v"), std::invalid_argument);
  EXPECT_NO_THROW(RequireAtLeast(3, 3, "v"));
  EXPECT_THROW(RequireAtLeast(kNaN, 3, "v"), std::invalid_argument);
  EXPECT_NO_THROW(RequireInRange(0.0, 0.0, 1.0, "v"));
  EXPECT_NO_THROW(RequireInRange(1.0, 0.0, 1.0, "v"));
  EXPECT_THROW(RequireInRange(kNaN, 0.0, 1.0, "v"), std::invalid_argument);
  EXPECT_NO_THROW(RequireFinite(Eigen::Matrix2d::Identity(), "M"));
  EXPECT_THROW(RequireFinite(Eigen::Vector2d(kInf, 0.0), "M"), std::invalid_argument);
  EXPECT_THAT(MessageOf([] { RequirePositive(kNaN, "v"); }), HasSubstr("v = nan"));
}

}  // namespace
}  // namespace aperture::control
