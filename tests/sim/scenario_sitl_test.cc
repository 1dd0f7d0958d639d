// Scenario -> SITL glue: the LED scenario's world-fixed camera, start pose and body-attached
// target carry over, so the target flies with the simulated vehicle in the rendered frames.
#include "sim/scenario/scenario_sitl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>

#include "sim/sitl/ground_truth_autopilot.h"

namespace aperture::sim {
namespace {

TEST(ScenarioSitlTest, LedTargetFliesWithTheVehicleInFrames) {
  ScenarioParams scenario_params = LoadScenarioParams(ScenarioConfig("led"));
  scenario_params.cameras.front().second.width = 188;  // small frames keep the test fast
  scenario_params.cameras.front().second.height = 120;
  Scenario scenario = BuildScenario(scenario_params);
  SitlRunnerParams params;
  params.duration_s = 0.1;
  ConfigureSitlFromScenario(scenario, &params);
  ASSERT_EQ(params.cameras.size(), 1u);
  ASSERT_TRUE(params.cameras[0].T_WC_fixed.has_value());  // the ground camera is world-mounted
  EXPECT_TRUE(params.initial_state.p_WB.isApprox(scenario.T_WB_start().translation()));
  EXPECT_TRUE(params.cameras[0].effects.infrared);
  // Rate, latency and disturbances of the scenario (C.4.3: 40 Hz poses; gusts and a push).
  EXPECT_DOUBLE_EQ(params.cameras[0].rate_hz, scenario_params.cameras.front().second.rate_hz);
  EXPECT_DOUBLE_EQ(params.cameras[0].latency_s, scenario_params.cameras.front().second.latency_s);
  EXPECT_GT(params.cameras[0].latency_s, 0.0);
  EXPECT_EQ(params.disturbances.pushes.size(), scenario_params.disturbances.pushes.size());
  EXPECT_FALSE(params.disturbances.gusts.empty());
  // The target is carried by the vehicle: not an obstacle to it (else the run ends at once).
  const auto& ignored = params.collision.ignored_objects;
  EXPECT_NE(std::find(ignored.begin(), ignored.end(), "led_target"), ignored.end());

  GroundTruthAutopilotParams autopilot_params;
  // Hover 0.3 m beside the start: the vehicle moves, and with it the target.
  autopilot_params.waypoints.push_back({params.initial_state.p_WB + Eigen::Vector3d(0.3, 0, 0)});
  GroundTruthAutopilot autopilot(params.dynamics.vehicle, autopilot_params);
  SitlRunner runner(params, &scenario.scene());
  SitlHooks hooks = MakeScenarioHooks(&scenario);
  int frames = 0;
  int led_pixels = 0;
  const int led0 = scenario.scene().FindId("led0");
  hooks.on_frame = [&](int, const CapturedFrame& frame, const control::QuadState& state) {
    ++frames;
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.linear() = state.q_WB.toRotationMatrix();
    T_WB.translation() = state.p_WB;
    EXPECT_TRUE(scenario.scene().object("led_target").T_WO.isApprox(T_WB, 1e-9));
    led_pixels += cv::countNonZero(frame.object_id == led0);
  };
  const SitlResult result = runner.Run(autopilot, hooks);
  EXPECT_EQ(result.outcome, SitlResult::Outcome::kDurationReached) << result.reason;
  EXPECT_GE(frames, 4);      // 40 Hz over 0.1 s
  EXPECT_GT(led_pixels, 0);  // the LED is drawn where the moving target carries it
}

}  // namespace
}  // namespace aperture::sim
