// The emulated initialization of the recovery's vision pipeline (thesis B.3.2 stage 3, B.4.2's
// failure mode): when it initializes, when it cannot, and what its estimate is.
#include "sim/sitl/visual_initialization.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <optional>

namespace aperture::sim {
namespace {

// Level flight at `height_m` drifting along x at `speed_mps`, sampled at 100 Hz.
control::QuadState Drifting(double t_s, double height_m, double speed_mps) {
  control::QuadState state;
  state.t_s = t_s;
  state.p_WB = Eigen::Vector3d(speed_mps * t_s, 0.0, height_m);
  state.v_W = Eigen::Vector3d(speed_mps, 0.0, 0.0);
  return state;
}

VisualInitializationParams Noiseless() {
  VisualInitializationParams params;
  params.position_noise_m = 0.0;
  params.velocity_noise_mps = 0.0;
  params.scale_noise = 0.0;
  return params;
}

// Steps until initialized (or `seconds` pass); returns the time of initialization.
std::optional<double> FlyUntilInitialized(VisualInitialization* vision, double height_m,
                                          double speed_mps, double seconds,
                                          double estimated_height_m) {
  for (int k = 0; k <= static_cast<int>(seconds * 100.0); ++k) {
    if (vision->Update(Drifting(0.01 * k, height_m, speed_mps), true, estimated_height_m)) {
      return 0.01 * k;
    }
  }
  return std::nullopt;
}

TEST(VisualInitializationTest, InitializesOnceTheBaselineIsATenthOfTheHeight) {
  VisualInitialization vision(Noiseless(), 1);
  // 0.3 m/s at 1.5 m: 0.15 m of translation after 0.5 s.
  const std::optional<double> t_s = FlyUntilInitialized(&vision, 1.5, 0.3, 2.0, 1.5);
  ASSERT_TRUE(t_s.has_value());
  EXPECT_NEAR(*t_s, 0.5, 0.011);
  EXPECT_TRUE(vision.initialized());
  EXPECT_DOUBLE_EQ(vision.initialized_at_s(), *t_s);
}

TEST(VisualInitializationTest, TooCloseTooFastTooTiltedOrNotAskedItNeverInitializes) {
  {
    VisualInitialization vision(Noiseless(), 1);  // 0.2 m: below min_height_m
    EXPECT_FALSE(FlyUntilInitialized(&vision, 0.2, 0.3, 3.0, 0.2).has_value());
  }
  {
    VisualInitialization vision(Noiseless(), 1);  // 4 m/s at 1 m: flow 4 rad/s > 3
    EXPECT_FALSE(FlyUntilInitialized(&vision, 1.0, 4.0, 3.0, 1.0).has_value());
    EXPECT_EQ(vision.baseline_m(), 0.0);
  }
  {
    VisualInitialization vision(Noiseless(), 1);  // the same speed 2 m higher: flow 1.33 rad/s
    EXPECT_TRUE(FlyUntilInitialized(&vision, 3.0, 4.0, 3.0, 3.0).has_value());
  }
  {
    VisualInitialization vision(Noiseless(), 1);  // tilted 30 deg: the ground not in view
    for (int k = 0; k < 300; ++k) {
      control::QuadState state = Drifting(0.01 * k, 1.5, 0.3);
      state.q_WB = Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitX());
      EXPECT_FALSE(vision.Update(state, true, 1.5));
    }
  }
  {
    VisualInitialization vision(Noiseless(), 1);  // the recovery does not ask for it yet
    for (int k = 0; k < 300; ++k) {
      EXPECT_FALSE(vision.Update(Drifting(0.01 * k, 1.5, 0.3), false, 1.5));
    }
  }
}

TEST(VisualInitializationTest, LosingTheFeaturesRestartsTheBaseline) {
  VisualInitialization vision(Noiseless(), 1);
  for (int k = 0; k < 40; ++k) vision.Update(Drifting(0.01 * k, 1.5, 0.3), true, 1.5);
  EXPECT_NEAR(vision.baseline_m(), 0.117, 0.004);
  control::QuadState spinning = Drifting(0.40, 1.5, 0.3);
  spinning.omega_B = Eigen::Vector3d(4.0, 0.0, 0.0);  // flow 4.2 rad/s
  vision.Update(spinning, true, 1.5);
  EXPECT_EQ(vision.baseline_m(), 0.0);
  // Another 0.5 s of tracking from there.
  for (int k = 41; k < 90; ++k) {
    EXPECT_FALSE(vision.Update(Drifting(0.01 * k, 1.5, 0.3), true, 1.5));
  }
  EXPECT_TRUE(vision.Update(Drifting(0.92, 1.5, 0.3), true, 1.5));
}

TEST(VisualInitializationTest, TheEstimateIsLateScaledByTheHeightEstimateAndRotated) {
  VisualInitializationParams params = Noiseless();
  params.offset_W = Eigen::Vector3d(1.0, -2.0, 0.0);
  VisualInitialization vision(params, 1);
  // The height filter reads 1.65 m at 1.5 m: scale 1.1, as SVO initialized on that height.
  const std::optional<double> t_init_s = FlyUntilInitialized(&vision, 1.5, 0.3, 2.0, 1.65);
  ASSERT_TRUE(t_init_s.has_value());
  EXPECT_NEAR(vision.scale(), 1.1, 1e-12);
  const Eigen::Matrix3d R_VW = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  vision.SetVisionRotation(R_VW);
  EXPECT_FALSE(vision.Estimate().has_value());  // latency_s (30 ms) not yet passed
  double t_s = *t_init_s;
  for (int k = 0; k < 10; ++k) {
    t_s += 0.01;
    vision.Update(Drifting(t_s, 1.5, 0.3), true, 1.65);
  }
  const std::optional<control::QuadState> estimate = vision.Estimate();
  ASSERT_TRUE(estimate.has_value());
  const control::QuadState late = Drifting(t_s - 0.03, 1.5, 0.3);
  EXPECT_NEAR(estimate->t_s, late.t_s, 1e-9);
  EXPECT_TRUE(estimate->p_WB.isApprox(1.1 * (R_VW * late.p_WB) + params.offset_W, 1e-9));
  EXPECT_TRUE(estimate->v_W.isApprox(1.1 * (R_VW * late.v_W), 1e-9));
}

TEST(VisualInitializationTest, NoiseHasTheStatedSpread) {
  VisualInitializationParams params = Noiseless();
  params.position_noise_m = 0.01;
  VisualInitialization vision(params, 7);
  ASSERT_TRUE(FlyUntilInitialized(&vision, 1.5, 0.3, 2.0, 1.5).has_value());
  double sum_squared = 0.0;
  const int n = 2000;
  for (int k = 0; k < n + 10; ++k) {
    const double t_s = 1.0 + 0.01 * k;
    vision.Update(Drifting(t_s, 1.5, 0.3), true, 1.5);
    if (k < 10) continue;  // the delay line fills with the states after the jump to 1 s
    sum_squared += (vision.Estimate()->p_WB - Drifting(t_s - 0.03, 1.5, 0.3).p_WB).squaredNorm();
  }
  EXPECT_NEAR(std::sqrt(sum_squared / (3.0 * n)), 0.01, 0.001);
}

TEST(VisualInitializationTest, BadParametersAreNamed) {
  VisualInitializationParams params;
  params.latency_s = -0.01;
  try {
    VisualInitialization vision(params, 1);
    FAIL() << "accepted a negative latency";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("latency_s"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace aperture::sim
