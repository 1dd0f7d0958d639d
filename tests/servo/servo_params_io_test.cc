#include "servo/servo_params_io.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "config/config_tree.h"
#include "free_camera_simulation.h"

namespace aperture::servo {
namespace {

TEST(ServoParamsIo, LoadsEverySectionAndKeepsDefaults) {
  config::ParamReader reader(YAML::Load(R"(
servo:
  law: pid
  moments: {yaw: orientation, gain: {at_zero_per_s: 2.0}}
  pid: {kp_mps: 1.5, forward_pitch_deg: 5.0}
tag_servo: {gain: {at_zero_per_s: 1.0, at_infinity_per_s: 1.0}, compensate_target_motion: false}
)"),
                             "servo.yaml");
  GapServoParams gap;
  PointServoParams tag;
  reader.ReadSection("servo", &gap);
  reader.ReadSection("tag_servo", &tag);
  reader.RejectUnknownKeys();
  EXPECT_EQ(gap.law, GapServoLaw::kPid);
  EXPECT_EQ(gap.moments.yaw, YawMode::kOrientation);
  EXPECT_EQ(gap.moments.gain.at_zero_per_s, 2.0);
  EXPECT_EQ(gap.moments.gain.at_infinity_per_s, ServoGain().at_infinity_per_s);
  EXPECT_EQ(gap.pid.kp_mps, 1.5);
  EXPECT_EQ(gap.pid.forward_pitch_deg, 5.0);
  EXPECT_EQ(gap.pid.ki_mps2, PidServoParams().ki_mps2);
  EXPECT_EQ(tag.gain.at_infinity_per_s, 1.0);  // equal gains: a constant lambda
  EXPECT_FALSE(tag.compensate_target_motion);
}

TEST(ServoParamsIo, SetSelectsTheLaw) {
  const config::ConfigTree tree =
      config::ConfigTree::FromCommandLine("servo: {law: moments}", {}, {"servo.law=pid"});
  config::ParamReader root = tree.Reader();
  GapServoParams params;
  root.ReadSection("servo", &params);
  EXPECT_EQ(params.law, GapServoLaw::kPid);
  // The selected law is the one that runs: the PID flies forward at g tan(theta_0) / d_x.
  GapServo servo(params, testing::ForwardCameraMount(), 0.5);
  EXPECT_EQ(servo.law(), GapServoLaw::kPid);
  OpeningView view;
  view.safe_point_n = Eigen::Vector2d::Zero();
  EXPECT_NEAR(servo.Step(view).reference.v_B.x(), 9.81 * std::tan(3.0 * M_PI / 180.0) / 0.5, 1e-12);
}

// Unknown keys, unknown enum names and values that fail Validate() name the source and the key.
TEST(ServoParamsIo, RejectsBadValuesNamingTheKey) {
  const auto message_of = [](const std::string& yaml) {
    try {
      config::ParamReader reader(YAML::Load(yaml), "servo.yaml");
      GapServoParams params;
      reader.ReadSection("servo", &params);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message_of("servo: {law: visual}").find("moments, pid"), std::string::npos);
  EXPECT_NE(message_of("servo: {lawz: pid}").find("lawz"), std::string::npos);
  EXPECT_NE(message_of("servo: {moments: {yaw: roll}}").find("hold, orientation"),
            std::string::npos);
  EXPECT_NE(message_of("servo: {pid: {kp: 1}}").find("servo.pid.kp"), std::string::npos);
  EXPECT_NE(message_of("servo: {pid: {forward_pitch_deg: 40}}").find("forward_pitch_deg"),
            std::string::npos);
  EXPECT_NE(message_of("servo: {moments: {gain: {at_zero_per_s: 0.5}}}").find("at_infinity_per_s"),
            std::string::npos);
  EXPECT_NE(message_of("servo: {pid: {kd_m: -1}}").find("servo.yaml"), std::string::npos);
}

}  // namespace
}  // namespace aperture::servo
