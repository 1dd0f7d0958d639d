// Scenario -> SITL glue: the LED scenario's world-fixed camera, start pose and body-attached
// target carry over, so the target flies with the simulated vehicle in the rendered frames.
#include "sim/scenario/scenario_sitl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

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

// The gap scenario with a 64 x 48 camera (cheap frames) and the given --set items.
Scenario SmallGapScenario(std::vector<std::string> set_items) {
  set_items.insert(set_items.begin(), {"cameras.front.width=64", "cameras.front.height=48",
                                       "cameras.front.supersampling=1"});
  return BuildScenario(LoadScenarioParams(ScenarioConfig("gap", {}, set_items)));
}

// Standard deviation of the delivered accelerometer z readings (hovering: specific force ~ g).
double AccelZSpread(const SitlResult& result) {
  double sum = 0.0, sum_sq = 0.0;
  for (const perception::ImuSample& sample : result.imu) {
    sum += sample.specific_force_B.z();
    sum_sq += sample.specific_force_B.z() * sample.specific_force_B.z();
  }
  const double n = static_cast<double>(result.imu.size());
  return std::sqrt(std::max(0.0, sum_sq / n - (sum / n) * (sum / n)));
}

SitlResult HoverAtStart(const Scenario& scenario, SitlRunnerParams* params) {
  params->duration_s = 0.6;
  ConfigureSitlFromScenario(scenario, params);
  GroundTruthAutopilotParams autopilot_params;
  autopilot_params.waypoints.push_back({params->initial_state.p_WB});
  GroundTruthAutopilot autopilot(params->dynamics.vehicle, autopilot_params);
  return SitlRunner(*params, &scenario.scene()).Run(autopilot);
}

TEST(ScenarioSitlTest, DynamicsImuRangeCollisionSitlAndDropKeysReachTheRunner) {
  const Scenario scenario = SmallGapScenario(
      {"dynamics.vehicle.rotor.time_constant_up_s=0.03", "dynamics.vehicle.mass_kg=0.5",
       "imu.accel_noise_density=0.2", "range.noise_sigma_m=0.05", "collision.body_radius_m=0.1",
       "sitl.command_latency_s=0.02", "sitl.control_rate_hz=50",
       "cameras.front.drop_probability=0.5"});
  SitlRunnerParams params;
  const SitlResult result = HoverAtStart(scenario, &params);
  EXPECT_DOUBLE_EQ(params.dynamics.vehicle.rotor.time_constant_up_s, 0.03);
  EXPECT_DOUBLE_EQ(params.dynamics.vehicle.mass_kg, 0.5);
  EXPECT_DOUBLE_EQ(params.imu.accel_noise_density, 0.2);
  EXPECT_DOUBLE_EQ(params.range.noise_sigma_m, 0.05);
  EXPECT_DOUBLE_EQ(params.collision.body_radius_m, 0.1);
  EXPECT_DOUBLE_EQ(params.command_latency_s, 0.02);
  EXPECT_DOUBLE_EQ(params.control_rate_hz, 50.0);
  ASSERT_EQ(params.cameras.size(), 1u);
  EXPECT_DOUBLE_EQ(params.cameras[0].drop_probability, 0.5);

  // And they act: half the frames are lost, the accelerometer is noisier, 50 Hz control.
  SitlRunnerParams nominal_params;
  const SitlResult nominal = HoverAtStart(SmallGapScenario({}), &nominal_params);
  EXPECT_EQ(result.outcome, SitlResult::Outcome::kDurationReached) << result.reason;
  EXPECT_EQ(nominal.outcome, SitlResult::Outcome::kDurationReached) << nominal.reason;
  ASSERT_EQ(result.cameras.size(), 1u);
  ASSERT_EQ(nominal.cameras.size(), 1u);
  EXPECT_EQ(nominal.cameras[0].frames_dropped, 0);
  // 31 frames due (50 Hz over 0.6 s); a fair coin drops 8..23 of them with probability > 0.99.
  EXPECT_GE(result.cameras[0].frames_dropped, 8);
  EXPECT_LE(result.cameras[0].frames_dropped, 23);
  EXPECT_EQ(result.commands.size(), 31u);   // 50 Hz over [0, 0.6] s
  EXPECT_EQ(nominal.commands.size(), 61u);  // the default 100 Hz
  // White noise of density 0.2 vs the default 3.9e-3 at 500 Hz: sigma = density * sqrt(rate)
  // ~ 4.5 vs 0.09 m/s^2 (imu_sensor.h), far above the hover's own accelerations.
  EXPECT_GT(AccelZSpread(result), 2.0);
  EXPECT_LT(AccelZSpread(nominal), 0.5);
}

// The flight controller's torque observer: on by default in every scenario (the forest too since
// its turn to the goal), and the key reaches the runner.
TEST(ScenarioSitlTest, TheTorqueObserverKeyReachesTheFlightController) {
  const auto observer_time_constant_s = [](const std::string& name,
                                           const std::vector<std::string>& set_items) {
    const Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig(name, {}, set_items)));
    SitlRunnerParams params;
    ConfigureSitlFromScenario(scenario, &params);
    return params.flight_controller.low_level.torque_observer_time_constant_s;
  };
  EXPECT_EQ(observer_time_constant_s("gap", {}), SitlRunnerParams().flight_controller.low_level
                                                     .torque_observer_time_constant_s);
  EXPECT_GT(observer_time_constant_s("gap", {}), 0.0);
  EXPECT_EQ(observer_time_constant_s("forest", {"forest.trees=0", "forest.boxes=0"}),
            observer_time_constant_s("gap", {}));
  EXPECT_EQ(observer_time_constant_s("forest", {"forest.trees=0", "forest.boxes=0",
                                                "sitl.torque_observer_time_constant_s=0"}),
            0.0);
  EXPECT_EQ(observer_time_constant_s("gap", {"sitl.torque_observer_time_constant_s=0.25"}), 0.25);
}

TEST(ScenarioSitlTest, AbsentSitlBlocksLeaveTheCallersParams) {
  const Scenario scenario = SmallGapScenario({});
  SitlRunnerParams params;
  params.imu.accel_noise_density = 0.1;
  params.control_rate_hz = 200.0;
  params.dynamics.vehicle.mass_kg = 0.6;
  ConfigureSitlFromScenario(scenario, &params);
  EXPECT_DOUBLE_EQ(params.imu.accel_noise_density, 0.1);
  EXPECT_DOUBLE_EQ(params.control_rate_hz, 200.0);
  EXPECT_DOUBLE_EQ(params.dynamics.vehicle.mass_kg, 0.6);
}

TEST(ScenarioSitlTest, UnknownKeysInTheSitlBlocksAreRejectedByName) {
  for (const std::string key :
       {"dynamics.vehicle.rotor.time_constant_up", "dynamics.rotor_lag", "imu.noise",
        "range.latency_s", "collision.radius_m", "sitl.duration_s", "cameras.front.drop_rate"}) {
    try {
      LoadScenarioParams(ScenarioConfig("gap", {}, {key + "=1"}));
      ADD_FAILURE() << "unknown key " << key << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("unknown key '" + key + "'"), std::string::npos)
          << e.what();
    }
  }
}

TEST(ScenarioSitlTest, InvalidSitlValuesAreRejectedNamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"cameras.front.drop_probability=1.5", "cameras.front.drop_probability"},
      {"dynamics.vehicle.mass_kg=-1", "dynamics.vehicle"},
      {"imu.rate_hz=0", "imu"},
      {"sitl.torque_observer_time_constant_s=-0.1", "torque_observer_time_constant_s"}};
  for (const auto& [item, key] : cases) {
    try {
      LoadScenarioParams(ScenarioConfig("gap", {}, {item}));
      ADD_FAILURE() << item << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace aperture::sim
