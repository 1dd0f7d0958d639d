#include "sim/control_params_io.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <functional>
#include <stdexcept>
#include <string>

#include "tests/support/message_of.h"
#include "tests/support/param_round_trip.h"

namespace aperture::sim {
namespace {

using test_support::MessageOf;

ControlStackParams LoadControlParams(const std::string& yaml) {
  config::ParamReader reader(YAML::Load(yaml), "control.yaml");
  ControlStackParams params;
  LoadParams(reader, &params);
  return params;
}

using BodyRateLaw = control::LowLevelControllerParameters::BodyRateLaw;
using Mixing = control::MixerParameters::Mixing;
using Saturation = control::MixerParameters::Saturation;

TEST(ControlParamsIoTest, DefaultsAreTheThesisStack) {
  const ControlStackParams params = LoadControlParams("{}");
  EXPECT_TRUE(params.position.compensate_rotor_drag);
  EXPECT_EQ(BodyRateName(params.low_level), "lqr");
  EXPECT_EQ(params.low_level.mixer.mixing, Mixing::kIterative);
  EXPECT_EQ(params.low_level.mixer.saturation, Saturation::kPrioritized);
  EXPECT_EQ(params.low_level.torque_observer_time_constant_s, 0.0);  // the thesis' law
}

TEST(ControlParamsIoTest, SelectsEveryBaselineAndGains) {
  const ControlStackParams params = LoadControlParams(R"(
drag_compensation: false
body_rate: p_high
mixer: one_shot
saturation: clipping
assured_yaw_torque_Nm: 0.002
torque_observer_time_constant_s: 0.2
position: {p_xy_per_s2: 6, d_z_per_s: 7, p_rp_per_s: 12}
lqr: {state_weights: [1, 2, 3, 4, 5, 6]}
)");
  EXPECT_FALSE(params.position.compensate_rotor_drag);
  EXPECT_EQ(params.low_level.body_rate_law, BodyRateLaw::kProportional);
  EXPECT_EQ(params.low_level.proportional.rate_gains_per_s,
            control::ProportionalBodyRateParameters::HighGain().rate_gains_per_s);
  EXPECT_EQ(BodyRateName(params.low_level), "p_high");
  EXPECT_EQ(params.low_level.mixer.mixing, Mixing::kOneShot);
  EXPECT_EQ(params.low_level.mixer.saturation, Saturation::kClip);
  EXPECT_EQ(params.low_level.mixer.assured_yaw_torque_Nm, 0.002);
  EXPECT_EQ(params.low_level.torque_observer_time_constant_s, 0.2);
  EXPECT_EQ(params.position.p_xy_per_s2, 6.0);
  EXPECT_EQ(params.position.p_z_per_s2, control::PositionControllerParams().p_z_per_s2);
  EXPECT_EQ(params.position.d_z_per_s, 7.0);
  EXPECT_EQ(params.position.attitude.p_rp_per_s, 12.0);
  EXPECT_EQ(params.low_level.lqr.state_weights(5), 6.0);

  const ControlStackParams low = LoadControlParams("body_rate: p_low");
  EXPECT_EQ(low.low_level.body_rate_law, BodyRateLaw::kProportional);
  EXPECT_EQ(low.low_level.proportional.rate_gains_per_s,
            control::ProportionalBodyRateParameters::LowGain().rate_gains_per_s);
  EXPECT_EQ(BodyRateName(low.low_level), "p_low");
}

TEST(ControlParamsIoTest, UnknownKeyIsNamedWithTheKnownKeys) {
  const std::string error = MessageOf([] { LoadControlParams("drag_compensaton: true"); });
  EXPECT_NE(error.find("drag_compensaton"), std::string::npos) << error;
  EXPECT_NE(error.find("drag_compensation"), std::string::npos) << error;
  const std::string nested = MessageOf([] { LoadControlParams("position: {p_xy: 3}"); });
  EXPECT_NE(nested.find("position.p_xy"), std::string::npos) << nested;
}

TEST(ControlParamsIoTest, BadEnumValueListsTheAllowedValues) {
  const std::string error = MessageOf([] { LoadControlParams("body_rate: pid"); });
  EXPECT_NE(error.find("body_rate"), std::string::npos) << error;
  EXPECT_NE(error.find("lqr, p_low, p_high"), std::string::npos) << error;
  const std::string mixer = MessageOf([] { LoadControlParams("mixer: fancy"); });
  EXPECT_NE(mixer.find("iterative, one_shot"), std::string::npos) << mixer;
  const std::string saturation = MessageOf([] { LoadControlParams("saturation: none"); });
  EXPECT_NE(saturation.find("prioritized, clipping"), std::string::npos) << saturation;
}

TEST(ControlParamsIoTest, NonPhysicalValuesAreRejectedWithTheirName) {
  EXPECT_NE(
      MessageOf([] { LoadControlParams("lqr: {input_weights: [1, 0, 1]}"); }).find("input_weights"),
      std::string::npos);
  EXPECT_NE(
      MessageOf([] { LoadControlParams("position: {p_xy_per_s2: -1}"); }).find("control.yaml"),
      std::string::npos);
  EXPECT_NE(MessageOf([] {
              LoadControlParams("assured_yaw_torque_Nm: -1");
            }).find("assured_yaw_torque_Nm"),
            std::string::npos);
  EXPECT_NE(MessageOf([] {
              LoadControlParams("torque_observer_time_constant_s: -0.1");
            }).find("torque_observer_time_constant_s"),
            std::string::npos);
}

TEST(ControlParamsIoTest, RoundTripsThroughItsDump) {
  test_support::ExpectRoundTrip(ControlStackParams{});  // lqr -> p_low by the perturbation
  ControlStackParams custom;
  custom.low_level.body_rate_law = BodyRateLaw::kProportional;
  custom.low_level.proportional.rate_gains_per_s = Eigen::Vector3d(21.0, 22.0, 9.0);
  const std::string yaml = config::DumpYaml(custom);
  EXPECT_NE(yaml.find("body_rate: p_custom"), std::string::npos) << yaml;
  const ControlStackParams loaded = LoadControlParams(yaml);
  EXPECT_EQ(loaded.low_level.body_rate_law, BodyRateLaw::kProportional);
  EXPECT_EQ(loaded.low_level.proportional.rate_gains_per_s, Eigen::Vector3d(21.0, 22.0, 9.0));
}

// A preset set over a dumped configuration wins: the dump of a preset carries no gains.
TEST(ControlParamsIoTest, PresetOverADumpedPresetTakesEffect) {
  ControlStackParams low = LoadControlParams("body_rate: p_low");
  YAML::Node dump = config::DumpParams(low);
  EXPECT_FALSE(dump["p_rate_gains_per_s"]);
  dump["body_rate"] = "p_high";
  config::ParamReader reader(dump, "dump.yaml");
  ControlStackParams loaded;
  LoadParams(reader, &loaded);
  EXPECT_EQ(BodyRateName(loaded.low_level), "p_high");
}

}  // namespace
}  // namespace aperture::sim
