#include "planning/led_hover_autopilot.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "perception/camera/pinhole_camera.h"

namespace aperture::planning {
namespace {

using ::testing::HasSubstr;

TEST(LedHoverAutopilotTest, RejectsBadParameters) {
  const control::VehicleParameters vehicle;
  const auto camera = std::make_shared<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{376.0, 376.0, 375.5, 239.5});
  const perception::LedConfiguration leds = perception::LedConfiguration::Default();
  LedHoverAutopilotParams params;
  EXPECT_NO_THROW(LedHoverAutopilot(vehicle, leds, camera, params));
  EXPECT_THROW(LedHoverAutopilot(vehicle, leds, nullptr, params), std::invalid_argument);
  {
    LedHoverAutopilotParams bad = params;
    bad.camera_id = -1;
    EXPECT_THROW(LedHoverAutopilot(vehicle, leds, camera, bad), std::invalid_argument);
  }
  {
    LedHoverAutopilotParams bad = params;
    bad.T_WC.linear() *= 2.0;
    try {
      LedHoverAutopilot(vehicle, leds, camera, bad);
      FAIL() << "a scaled T_WC was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr("LedHoverAutopilotParams.T_WC"));
    }
  }
  {
    LedHoverAutopilotParams bad = params;
    bad.setpoint.p_W.z() = std::nan("");
    EXPECT_THROW(LedHoverAutopilot(vehicle, leds, camera, bad), std::invalid_argument);
  }
  {
    LedHoverAutopilotParams bad = params;
    bad.hold.integral_gain_per_s3 = -1.0;
    EXPECT_THROW(LedHoverAutopilot(vehicle, leds, camera, bad), std::invalid_argument);
  }
}

TEST(LedHoverAutopilotTest, WithoutFramesItCommandsNothingAndIgnoresOtherCameras) {
  const control::VehicleParameters vehicle;
  const auto camera = std::make_shared<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{376.0, 376.0, 375.5, 239.5});
  LedHoverAutopilotParams params;
  params.camera_id = 1;
  LedHoverAutopilot autopilot(vehicle, perception::LedConfiguration::Default(), camera, params);
  EXPECT_FALSE(autopilot.UsesGroundTruth());
  perception::Frame frame;
  frame.camera_id = 0;  // not the LED camera
  frame.image = cv::Mat(10, 10, CV_8UC1, cv::Scalar(0));
  autopilot.OnFrame(frame);
  EXPECT_EQ(autopilot.counts().frames, 0);
  EXPECT_EQ(autopilot.Step(0.01).kind, perception::AutopilotCommand::Kind::kNone);
  EXPECT_EQ(autopilot.status(), "waiting for pose");
}

}  // namespace
}  // namespace aperture::planning
