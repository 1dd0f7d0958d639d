// Ego-dynamic space (seed 003 Sec. III-B): d_eff solves d_eff^2 / (2 dt^2 a_b) + d_eff = d_obs,
// so the distance covered in dt plus the braking distance equals the obstacle distance; it grows
// monotonically, stays below d_obs, and is <= 0 exactly when the obstacle is within the margin.
#include "planning/mono_nav/ego_dynamic_space.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aperture::planning {
namespace {

TEST(EgoDynamicSpace, EffectiveDistanceSolvesTheBrakingBalance) {
  EgoDynamicParams params;
  params.response_time_s = 0.4;
  params.max_deceleration_mps2 = 2.5;
  double previous = -1e9;
  for (double d_obs = 0.0; d_obs <= 40.0; d_obs += 0.25) {
    const double d_eff = EffectiveDistance(d_obs, params);
    const double v = AllowedSpeed(d_eff, params);
    // v dt + v^2 / (2 a_b) = d_obs (Sec. III-B (4)-(6)).
    EXPECT_NEAR(v * params.response_time_s + v * v / (2.0 * params.max_deceleration_mps2), d_obs,
                1e-9 * (1.0 + d_obs));
    EXPECT_LE(d_eff, d_obs + 1e-12);
    EXPECT_GT(d_eff, previous);
    previous = d_eff;
  }
  EXPECT_DOUBLE_EQ(EffectiveDistance(0.0, params), 0.0);
  EXPECT_LT(EffectiveDistance(-0.1, params), 0.0);  // inside the margin: imminent collision
  // No real root: the most negative value, still imminent.
  EXPECT_DOUBLE_EQ(EffectiveDistance(-100.0, params), -2.5 * 0.4 * 0.4);
  // Far away the braking term dominates: d_eff ~ sqrt(2 a_b dt^2 d_obs).
  EXPECT_NEAR(EffectiveDistance(1e6, params) / std::sqrt(2.0 * 2.5 * 0.16 * 1e6), 1.0, 1e-3);
}

TEST(EgoDynamicSpace, TransformsADepthMapWithTheErrorMargin) {
  EgoDynamicParams params;
  params.depth_error_margin_m = 0.5;
  cv::Mat depth = (cv::Mat_<float>(1, 3) << 0.4f, 2.5f, 40.0f);
  const cv::Mat d_eff = EgoDynamicTransform(depth, params);
  EXPECT_LT(d_eff.at<float>(0, 0), 0.0f);  // nearer than the margin
  EXPECT_NEAR(d_eff.at<float>(0, 1), EffectiveDistance(2.0, params), 1e-5);
  EXPECT_NEAR(d_eff.at<float>(0, 2), EffectiveDistance(39.5, params), 1e-4);
  EXPECT_THROW(EgoDynamicTransform(cv::Mat(1, 3, CV_64F), params), std::invalid_argument);
  params.max_deceleration_mps2 = 0.0;
  EXPECT_THROW(EgoDynamicTransform(depth, params), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
