#include "control/recovery_pipeline.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "control/constants.h"

namespace aperture::control {
namespace {

constexpr double kPipelineDt_s = 0.002;

TEST(RecoveryPipeline, RestartRecoversWithoutThrowAndInitializesHeightOnRequest) {
  // A vehicle hovering level at 1.2 m (IMU reads g along z_B) loses its vision estimate:
  // Restart() must run attitude -> vertical velocity -> height without any launch.
  RecoveryPipeline pipeline{VehicleParameters()};
  const Eigen::Vector3d f_hover(0.0, 0.0, kGravity_mps2);
  double t = 0.0;
  auto tick = [&](bool range) {
    t += kPipelineDt_s;
    pipeline.AddImu(t, f_hover, Eigen::Vector3d::Zero());
    if (range) pipeline.AddRange(1.2);
    return pipeline.Step(t);
  };
  for (int k = 0; k < 50; ++k) EXPECT_EQ(tick(true).stage, RecoveryStage::kWaitingForLaunch);
  EXPECT_FALSE(pipeline.launch_detector().launched());   // hover is not a launch
  EXPECT_FALSE(pipeline.height_filter().initialized());  // range ignored before the request

  pipeline.Restart(t);
  ASSERT_EQ(pipeline.state_machine().transitions().size(), 1u);
  EXPECT_EQ(pipeline.state_machine().stage(), RecoveryStage::kAttitude);
  EXPECT_EQ(tick(false).stage, RecoveryStage::kAttitude);  // level: exits after one step
  EXPECT_EQ(pipeline.state_machine().stage(), RecoveryStage::kVerticalVelocity);
  EXPECT_FALSE(pipeline.height_filter().initialized());
  tick(true);  // first range reading initializes the filter at the projected height
  ASSERT_TRUE(pipeline.height_filter().initialized());
  EXPECT_NEAR(pipeline.height_filter().estimate().z_m, 1.2, 1e-12);
  // The filter runs min_height_filter_time_s (0.3 s) before the stage can exit on |z_dot| < 0.3.
  int steps = 0;
  while (pipeline.state_machine().stage() == RecoveryStage::kVerticalVelocity && steps < 1000) {
    tick(true);
    ++steps;
  }
  EXPECT_EQ(pipeline.state_machine().stage(), RecoveryStage::kHeight);
  EXPECT_NEAR(steps * kPipelineDt_s, RecoveryParams().min_height_filter_time_s,
              2.5 * kPipelineDt_s);
  EXPECT_NEAR(pipeline.state_machine().reference_height_m(), 1.2, 1e-9);
}

TEST(RecoveryPipeline, ThrowIsDetectedFromRawImuSamples) {
  RecoveryPipeline pipeline{VehicleParameters()};
  double t = 0.0;
  for (int k = 0; k < 100; ++k) {  // held: |f| = g
    t += kPipelineDt_s;
    pipeline.AddImu(t, Eigen::Vector3d(0.0, 0.0, kGravity_mps2), Eigen::Vector3d::Zero());
    pipeline.Step(t);
  }
  int steps = 0;
  while (pipeline.state_machine().stage() == RecoveryStage::kWaitingForLaunch && steps < 100) {
    t += kPipelineDt_s;
    pipeline.AddImu(t, Eigen::Vector3d(0.0, 0.0, 0.4),
                    Eigen::Vector3d(5.0, 0.0, 0.0));  // free fall
    pipeline.Step(t);
    ++steps;
  }
  EXPECT_EQ(pipeline.state_machine().stage(), RecoveryStage::kAttitude);
  // (B.29): mean over 50 ms of {g, 0.4} falls below 0.44 + 2 after 80 % of the window is free
  // fall (41 ms), plus the command-then-transition step.
  EXPECT_NEAR(steps * kPipelineDt_s, 0.042, 0.004);
}

}  // namespace
}  // namespace aperture::control
