// Quick runs of the low-level control sections of `aperture bench control` (body_rate, mixer,
// saturation; thesis G.6): every summary key is written with a finite value, and the thesis'
// claims that a quick run already shows with a wide margin hold. Full-length figures come from
// `aperture bench control`.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "experiments/control/low_level_sections.h"
#include "output/html_report.h"

namespace aperture::experiments {
namespace {

nlohmann::json RunQuick(const ControlBenchSection& section) {
  ControlBenchOptions options;
  options.quick = true;
  options.vehicle.mismatch = false;  // vehicle = model (the mismatched bench: mismatch.md)
  nlohmann::json summary;
  output::HtmlReport report("test");
  section.run(options, &summary, &report);
  EXPECT_NE(report.ToHtml().find("<svg"), std::string::npos) << section.key << ": no plot";
  return summary.at(section.key);
}

void ExpectFinite(const nlohmann::json& object, const std::string& key) {
  ASSERT_TRUE(object.contains(key)) << key;
  ASSERT_TRUE(object.at(key).is_number()) << key;
  EXPECT_TRUE(std::isfinite(object.at(key).get<double>())) << key;
}

TEST(ControlBenchLowLevelSections, BodyRateLqrTracksRatesBetterThanLowGainP) {
  const nlohmann::json out = RunQuick(MakeBodyRateSection());
  for (const std::string controller : {"p_low", "p_high", "lqr"}) {
    for (const std::string key :
         {"rate_rmse", "position_rmse", "settling_time", "settling_time_std", "x_error_mean",
          "x_error_std", "thrust_angle_mean", "thrust_angle_std", "pitch_rate_error_mean",
          "pitch_rate_error_std"}) {
      ExpectFinite(out.at(controller), key);
    }
    // Table G.1's mean of |e_omega_y| is at most its RMS (RMS^2 = mean^2 + std^2).
    EXPECT_LE(out.at(controller).at("pitch_rate_error_mean").get<double>(),
              out.at(controller).at("pitch_rate_rmse").get<double>() + 1e-12);
    EXPECT_NEAR(std::hypot(out.at(controller).at("pitch_rate_error_mean").get<double>(),
                           out.at(controller).at("pitch_rate_error_std").get<double>()),
                out.at(controller).at("pitch_rate_rmse").get<double>(), 1e-9)
        << controller;
    EXPECT_GT(out.at(controller).at("settling_time").get<double>(), 0.0) << controller;
  }
  // Table G.1: the LQR almost halves the rate error of the low-gain P controller (acceptance
  // 0.6 x); measured 0.13 x on one round trip, so 0.6 is a wide margin.
  EXPECT_LT(out.at("lqr").at("rate_rmse").get<double>(),
            0.6 * out.at("p_low").at("rate_rmse").get<double>());
  // ... and tracks position better (measured 0.7 x; the gap to 1 is far above the noise).
  EXPECT_LT(out.at("lqr").at("position_rmse").get<double>(),
            out.at("p_low").at("position_rmse").get<double>());
  // Table G.1: the thrust direction follows the demand more closely with the LQR than with the
  // low-gain P (4.14 vs 5.55 deg).
  EXPECT_LT(out.at("lqr").at("thrust_angle_mean").get<double>(),
            out.at("p_low").at("thrust_angle_mean").get<double>());
  ASSERT_EQ(out.at("table_g1").size(), 8u);
  EXPECT_EQ(out.at("table_g1")[2].at("statistic"), "mu(theta) [deg]");
  EXPECT_NEAR(out.at("table_g1")[2].at("(c)").get<double>(),
              out.at("lqr").at("thrust_angle_mean").get<double>() * 180.0 / M_PI, 1e-9);
}

TEST(ControlBenchLowLevelSections, IterativeMixerHasSmallerYawErrorThanOneShot) {
  const nlohmann::json out = RunQuick(MakeMixerSection());
  for (const std::string key : {"yaw_rmse_iterative", "yaw_rmse_one_shot"}) {
    ExpectFinite(out, key);
  }
  // Table G.2: > 35 % lower with the iterative mixer; the quick hover measures ~70 %.
  EXPECT_LT(out.at("yaw_rmse_iterative").get<double>(),
            0.65 * out.at("yaw_rmse_one_shot").get<double>());
}

TEST(ControlBenchLowLevelSections, PrioritizedSaturationKeepsPositionWhereClippingDrifts) {
  const nlohmann::json out = RunQuick(MakeSaturationSection());
  for (const std::string scheme : {"prioritized", "clipping"}) {
    ExpectFinite(out.at(scheme), "xy_max_dev");
    ASSERT_TRUE(out.at(scheme).at("crashed").is_boolean()) << scheme;
  }
  EXPECT_FALSE(out.at("prioritized").at("crashed").get<bool>());
  EXPECT_EQ(out.at("assured_yaw_torque").get<double>(), 0.01);  // Fig. G.9
  // G.6.4: x and y stay close with prioritized saturation and deflect a lot with clipping
  // (acceptance 1/3; measured 0.32, so the test asserts the robust half).
  EXPECT_LT(out.at("prioritized").at("xy_max_dev").get<double>(),
            0.5 * out.at("clipping").at("xy_max_dev").get<double>());
}

// The same step on the mismatched bench vehicle (issue 21): the thrust limits are the true
// rotors' as the hover-calibrated flight controller knows them; prioritized saturation still
// holds x-y where clipping crashes (seeds 1-3: 0.16-0.20 m against 0.58-0.74 m).
TEST(ControlBenchLowLevelSections, PrioritizedSaturationStillBeatsClippingOnTheMismatchedVehicle) {
  ControlBenchOptions options;
  options.quick = true;
  nlohmann::json summary;
  output::HtmlReport report("test");
  ASSERT_TRUE(options.vehicle.mismatch);  // the bench default
  MakeSaturationSection().run(options, &summary, &report);
  const nlohmann::json& out = summary.at("saturation");
  EXPECT_FALSE(out.at("prioritized").at("crashed").get<bool>());
  EXPECT_TRUE(out.at("clipping").at("crashed").get<bool>());
  EXPECT_LT(out.at("prioritized").at("xy_max_dev").get<double>(),
            0.5 * out.at("clipping").at("xy_max_dev").get<double>());
}

}  // namespace
}  // namespace aperture::experiments
