#include "sim/sim_params_io.h"

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

template <typename Params>
Params LoadSimParams(const std::string& yaml) {
  config::ParamReader reader(YAML::Load(yaml), "test.yaml");
  Params params;
  LoadParams(reader, &params);
  return params;
}

TEST(SimParamsIoTest, LoadsVehicleAndDynamicsKeepingDefaultsForAbsentKeys) {
  const auto params = LoadSimParams<QuadrotorDynamicsParams>(R"(
vehicle:
  mass_kg: 0.6
  rotor_drag_D_per_s: [0.4, 0.3, 0.1]
  rotor_drag_B: [[1e-3, 0, 0], [0, 2e-3, 0], [0, 0, 3e-3]]
  rotor: {time_constant_down_s: 0.03}
  rotor_fitness: [1, 0.9, 1, 1]
max_integration_step_s: 0.0005
rotor_lag_enabled: false
)");
  EXPECT_EQ(params.vehicle.mass_kg, 0.6);
  EXPECT_EQ(params.vehicle.rotor_drag_D_per_s, Eigen::Vector3d(0.4, 0.3, 0.1));
  EXPECT_EQ(params.vehicle.rotor_drag_B(1, 1), 2e-3);
  EXPECT_EQ(params.vehicle.rotor.time_constant_down_s, 0.03);
  EXPECT_EQ(params.vehicle.rotor.time_constant_up_s, control::RotorParameters().time_constant_up_s);
  EXPECT_EQ(params.vehicle.rotor_fitness[1], 0.9);
  EXPECT_EQ(params.max_integration_step_s, 0.0005);
  EXPECT_FALSE(params.rotor_lag_enabled);
}

TEST(SimParamsIoTest, LoadsGustsAndPushesFromRows) {
  const auto params = LoadSimParams<DisturbanceParams>(R"(
steady_wind_W_mps: [1, 0, 0]
gusts: [[2.0, 0.5, 0, 3, 0]]
pushes: [[1.0, 0.5, 0, 0], [3.0, 0, 0, 0.2, 0, 0, 1e-3]]
)");
  ASSERT_EQ(params.gusts.size(), 1u);
  EXPECT_EQ(params.gusts[0].t_start_s, 2.0);
  EXPECT_EQ(params.gusts[0].duration_s, 0.5);
  EXPECT_EQ(params.gusts[0].wind_W_mps, Eigen::Vector3d(0, 3, 0));
  ASSERT_EQ(params.pushes.size(), 2u);
  EXPECT_EQ(params.pushes[0].impulse_W_Ns, Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(params.pushes[0].angular_impulse_B_Nms, Eigen::Vector3d::Zero());
  EXPECT_EQ(params.pushes[1].angular_impulse_B_Nms, Eigen::Vector3d(0, 0, 1e-3));
}

TEST(SimParamsIoTest, LoadsSensors) {
  const auto imu = LoadSimParams<ImuSensorParams>(
      "{rate_hz: 1000, latency_s: 0.001, seed: 42, stamp_at_delivery: true}");
  EXPECT_EQ(imu.rate_hz, 1000.0);
  EXPECT_EQ(imu.seed, 42u);
  EXPECT_TRUE(imu.stamp_at_delivery);
  const auto range = LoadSimParams<RangeSensorParams>("{max_range_m: 4, p_BS: [0.05, 0, -0.02]}");
  EXPECT_EQ(range.max_range_m, 4.0);
  EXPECT_EQ(range.p_BS, Eigen::Vector3d(0.05, 0, -0.02));
}

TEST(SimParamsIoTest, RejectsUnknownKeysMalformedRowsAndInvalidValuesNamingThem) {
  EXPECT_NE(MessageOf([] {
              LoadSimParams<QuadrotorDynamicsParams>("vehicle: {rotor: {tau_up: 0.01}}");
            }).find("tau_up"),
            std::string::npos);
  const std::string push_error =
      MessageOf([] { LoadSimParams<DisturbanceParams>("pushes: [[1.0, 0.5, 0]]"); });
  EXPECT_NE(push_error.find("pushes[0]"), std::string::npos) << push_error;
  const std::string imu_error =
      MessageOf([] { LoadSimParams<ImuSensorParams>("{latency_s: -1}"); });
  EXPECT_NE(imu_error.find("test.yaml"), std::string::npos) << imu_error;
  EXPECT_NE(imu_error.find("latency_s"), std::string::npos) << imu_error;
  const std::string mass_error =
      MessageOf([] { LoadSimParams<QuadrotorDynamicsParams>("vehicle: {mass_kg: 0}"); });
  EXPECT_NE(mass_error.find("mass_kg"), std::string::npos) << mass_error;
  EXPECT_NE(MessageOf([] { LoadSimParams<RangeSensorParams>("{seed: -3}"); }).find("seed"),
            std::string::npos);
}

// Dump -> load -> dump with every field off its default (tests/support/param_round_trip.h).
TEST(SimParamsIoTest, EveryStructRoundTripsThroughItsDump) {
  QuadrotorDynamicsParams dynamics;
  dynamics.vehicle.rotor_fitness = Eigen::Vector4d(0.9, 0.8, 0.95, 0.7);  // at most 1
  test_support::ExpectRoundTrip(dynamics);
  DisturbanceParams disturbances;
  disturbances.gusts.push_back({1.0, 0.5, Eigen::Vector3d(1.0, -2.0, 0.1)});
  disturbances.pushes.push_back({2.0, Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d::Zero()});
  disturbances.pushes.push_back({3.0, Eigen::Vector3d(0.1, 0.0, 0.0), Eigen::Vector3d(0, 0, 1e-3)});
  test_support::ExpectRoundTrip(disturbances);
  test_support::ExpectRoundTrip(ImuSensorParams{});
  test_support::ExpectRoundTrip(RangeSensorParams{});
  CollisionParams collision;
  collision.ignored_objects = {"led_target", "1"};
  test_support::ExpectRoundTrip(collision);
  test_support::ExpectRoundTrip(SitlRunnerParams{});
}

TEST(SimParamsIoTest, PushesDumpInTheShortFormWithoutAngularImpulse) {
  DisturbanceParams disturbances;
  disturbances.pushes.push_back({2.0, Eigen::Vector3d(0.5, 0.0, 0.0), Eigen::Vector3d::Zero()});
  disturbances.gusts.push_back({1.0, 0.25, Eigen::Vector3d(3.0, 0.0, 0.0)});
  const std::string yaml = config::DumpYaml(disturbances);
  EXPECT_NE(yaml.find("pushes: [[2, 0.5, 0, 0]]"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("gusts: [[1, 0.25, 3, 0, 0]]"), std::string::npos) << yaml;
}

}  // namespace
}  // namespace aperture::sim
