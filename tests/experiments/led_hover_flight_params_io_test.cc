// The `mission` section of `aperture sim led`: LedHoverFlightParams with its pose hold (filter,
// controller) and LED tracker, described once (experiments/led/led_hover_flight_params_io.h).
#include "experiments/led/led_hover_flight_params_io.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "tests/support/message_of.h"
#include "tests/support/param_round_trip.h"

namespace aperture::experiments {
namespace {

TEST(LedHoverFlightParamsIo, RoundTripsThroughItsDump) {
  test_support::ExpectRoundTrip(LedHoverFlightParams{});
}

TEST(LedHoverFlightParamsIo, LoadsNestedKeysAndNamesBadOnes) {
  config::ParamReader reader(
      YAML::Load("{hold: {integral_gain_per_s3: 2, controller: {p_xy_per_s2: 4}}, "
                 "tracker: {correspondence: {p3p_method: ap3p}}}"),
      "led.yaml");
  LedHoverFlightParams params;
  LoadParams(reader, &params);
  EXPECT_EQ(params.hold.integral_gain_per_s3, 2.0);
  EXPECT_EQ(params.hold.controller.p_xy_per_s2, 4.0);
  EXPECT_EQ(params.tracker.correspondence.p3p_method, perception::P3pMethod::kAp3p);
  EXPECT_EQ(params.recovery_radius_m, LedHoverFlightParams().recovery_radius_m);

  const std::string method = test_support::MessageOf([] {
    config::ParamReader bad(YAML::Load("{tracker: {correspondence: {p3p_method: epnp}}}"),
                            "led.yaml");
    LedHoverFlightParams p;
    LoadParams(bad, &p);
  });
  EXPECT_NE(method.find("tracker.correspondence.p3p_method"), std::string::npos) << method;
  EXPECT_NE(method.find("kneip, opengv, ap3p"), std::string::npos) << method;
  const std::string gain = test_support::MessageOf([] {
    config::ParamReader bad(YAML::Load("{hold: {integral_gain_per_s3: -1}}"), "led.yaml");
    LedHoverFlightParams p;
    LoadParams(bad, &p);
  });
  EXPECT_NE(gain.find("led.yaml"), std::string::npos) << gain;
  EXPECT_NE(gain.find("hold"), std::string::npos) << gain;
}

}  // namespace
}  // namespace aperture::experiments
