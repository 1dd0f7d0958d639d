// The faults of `aperture bench faults`: each changes what it names and nothing else, within the
// issue's ranges; the mission's model stays nominal.
#include "experiments/faults/fault_injection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "perception/camera/pinhole_camera.h"

namespace aperture::experiments {
namespace {

sim::SitlRunnerParams TwoCameraParams() {
  sim::SitlRunnerParams sitl;
  sitl.duration_s = 12.0;
  for (const char* name : {"front", "down"}) {
    sim::SitlCamera camera;
    camera.name = name;
    camera.model = std::make_shared<perception::PinholeCamera>(
        40, 30, perception::PinholeIntrinsics{20.0, 20.0, 19.5, 14.5});
    camera.latency_s = 0.01;
    camera.drop_probability = 0.1;
    sitl.cameras.push_back(camera);
  }
  return sitl;
}

TEST(FaultInjection, CatalogueHoldsTheIssuesRangesWithTheMiddleAsDefault) {
  EXPECT_EQ(FaultCatalogue().size(), 7u);
  const FaultSpec& drop = FindFault("frame_drop");
  EXPECT_DOUBLE_EQ(drop.DefaultLevel(), 0.25);
  EXPECT_DOUBLE_EQ(drop.TwiceDefaultLevel(), 0.5);
  const FaultSpec& imu = FindFault("imu_noise");
  EXPECT_DOUBLE_EQ(imu.low, 1.0);
  EXPECT_DOUBLE_EQ(imu.DefaultLevel(), 5.5);
  EXPECT_DOUBLE_EQ(imu.TwiceDefaultLevel(), 10.0);  // twice the excess noise: 9 = 2 x 4.5
  const std::vector<double> motor = FindFault("motor_loss").SweepLevels();
  const std::vector<double> expected = {0.0, 0.075, 0.15, 0.225, 0.3};
  ASSERT_EQ(motor.size(), expected.size());
  for (std::size_t i = 0; i < motor.size(); ++i) EXPECT_NEAR(motor[i], expected[i], 1e-15);
  try {
    FindFault("wind");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("perception_outage"), std::string::npos) << e.what();
  }
}

TEST(FaultInjection, NoFaultLevelLeavesTheParametersAsTheyWere) {
  const FaultDraw draw = DrawFault(3);
  for (const FaultSpec& fault : FaultCatalogue()) {
    sim::SitlRunnerParams sitl = TwoCameraParams();
    InjectFault(fault.kind, fault.low, draw, &sitl);
    EXPECT_EQ(sitl.cameras[0].drop_probability, 0.1) << fault.name;
    EXPECT_EQ(sitl.cameras[1].latency_s, 0.01) << fault.name;
    EXPECT_TRUE(sitl.cameras[0].outages.empty()) << fault.name;
    EXPECT_TRUE(sitl.disturbances.gusts.empty()) << fault.name;
    EXPECT_FALSE(sitl.flight_controller_model.has_value()) << fault.name;
    EXPECT_EQ(sitl.imu.accel_noise_density, sim::ImuSensorParams().accel_noise_density);
  }
}

TEST(FaultInjection, EachFaultChangesWhatItNames) {
  const FaultDraw draw = DrawFault(11);
  const sim::SitlRunnerParams nominal = TwoCameraParams();
  sim::SitlRunnerParams sitl = nominal;
  InjectFault(FaultKind::kFrameDrop, 0.5, draw, &sitl);
  for (const sim::SitlCamera& camera : sitl.cameras) {
    EXPECT_DOUBLE_EQ(camera.drop_probability, 1.0 - 0.9 * 0.5);  // independent of its own drops
  }
  sitl = nominal;
  InjectFault(FaultKind::kCameraLatency, 0.05, draw, &sitl);
  for (const sim::SitlCamera& camera : sitl.cameras) EXPECT_DOUBLE_EQ(camera.latency_s, 0.06);
  sitl = nominal;
  InjectFault(FaultKind::kImuNoise, 4.0, draw, &sitl);
  EXPECT_DOUBLE_EQ(sitl.imu.accel_noise_density, 4.0 * nominal.imu.accel_noise_density);
  EXPECT_DOUBLE_EQ(sitl.imu.gyro_noise_density, 4.0 * nominal.imu.gyro_noise_density);
  EXPECT_DOUBLE_EQ(sitl.imu.accel_bias_random_walk, 4.0 * nominal.imu.accel_bias_random_walk);
  EXPECT_DOUBLE_EQ(sitl.imu.gyro_bias_random_walk, 4.0 * nominal.imu.gyro_bias_random_walk);
  sitl = nominal;
  InjectFault(FaultKind::kAccelBias, 0.3, draw, &sitl);
  EXPECT_NEAR(sitl.imu.accel_bias_initial_B.norm(), 0.3, 1e-12);
  EXPECT_TRUE(sitl.imu.gyro_bias_initial_B.isZero());
  sitl = nominal;
  InjectFault(FaultKind::kGust, 5.0, draw, &sitl);
  ASSERT_EQ(sitl.disturbances.gusts.size(), 1u);
  const sim::WindGust& gust = sitl.disturbances.gusts[0];
  EXPECT_NEAR(gust.wind_W_mps.norm(), 5.0, 1e-12);
  EXPECT_EQ(gust.wind_W_mps.z(), 0.0);  // horizontal
  EXPECT_DOUBLE_EQ(gust.duration_s, 1.0);
  EXPECT_DOUBLE_EQ(gust.t_start_s, FaultOnsetS(draw, 12.0));
  EXPECT_GE(gust.t_start_s, 1.0);
  EXPECT_LE(gust.t_start_s, 4.0);  // in the first third of the flight
  sitl = nominal;
  InjectFault(FaultKind::kPerceptionOutage, 0.5, draw, &sitl);
  for (const sim::SitlCamera& camera : sitl.cameras) {
    ASSERT_EQ(camera.outages.size(), 1u);
    EXPECT_DOUBLE_EQ(camera.outages[0].start_s, FaultOnsetS(draw, 12.0));
    EXPECT_DOUBLE_EQ(camera.outages[0].end_s - camera.outages[0].start_s, 0.5);
  }
}

TEST(FaultInjection, WeakMotorIsUnknownToTheFlightController) {
  sim::SitlRunnerParams sitl = TwoCameraParams();
  const control::VehicleParameters nominal = sitl.dynamics.vehicle;
  InjectFault(FaultKind::kMotorLoss, 0.3, DrawFault(1), &sitl);
  EXPECT_DOUBLE_EQ(sitl.dynamics.vehicle.rotor_fitness(0), 0.7);
  EXPECT_EQ(sitl.dynamics.vehicle.rotor_fitness.tail<3>(), Eigen::Vector3d::Ones());
  ASSERT_TRUE(sitl.flight_controller_model.has_value());
  EXPECT_EQ(sitl.flight_controller_model->rotor_fitness, nominal.rotor_fitness);
  // A model set before (a mismatched vehicle's nominal one) is kept.
  sitl = TwoCameraParams();
  control::VehicleParameters model = nominal;
  model.mass_kg *= 1.1;
  sitl.flight_controller_model = model;
  InjectFault(FaultKind::kMotorLoss, 0.15, DrawFault(1), &sitl);
  EXPECT_DOUBLE_EQ(sitl.flight_controller_model->mass_kg, model.mass_kg);
}

TEST(FaultInjection, LevelsOutsideTheRangeAreRejected) {
  sim::SitlRunnerParams sitl = TwoCameraParams();
  const FaultDraw draw = DrawFault(2);
  EXPECT_THROW(InjectFault(FaultKind::kFrameDrop, 0.6, draw, &sitl), std::invalid_argument);
  EXPECT_THROW(InjectFault(FaultKind::kImuNoise, 0.5, draw, &sitl), std::invalid_argument);
  EXPECT_THROW(InjectFault(FaultKind::kGust, std::numeric_limits<double>::quiet_NaN(), draw, &sitl),
               std::invalid_argument);
}

TEST(FaultInjection, SettingsParseAsWrittenAndBadOnesAreNamed) {
  const FaultSetting weak = ParseFaultSetting("motor_loss=0.15");
  EXPECT_EQ(weak.fault->kind, FaultKind::kMotorLoss);
  EXPECT_DOUBLE_EQ(weak.level, 0.15);
  EXPECT_EQ(ParseFaultSetting("imu_noise=10").level, 10.0);
  for (const std::string text : {"wind=1", "motor_loss", "motor_loss=", "motor_loss=0.31",
                                 "gust=nan", "gust=1x", "imu_noise=0.5"}) {
    try {
      ParseFaultSetting(text);
      ADD_FAILURE() << text << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(text.substr(0, text.find('='))), std::string::npos)
          << e.what();
    }
  }
  // Sweep levels read as written: 3/4 of 0.3 is 0.225, not 0.22499999999999998.
  EXPECT_EQ(FindFault("motor_loss").LevelAt(0.75), 0.225);
}

TEST(FaultInjection, DrawsArePureFunctionsOfTheSeed) {
  const FaultDraw a = DrawFault(42), b = DrawFault(42), c = DrawFault(43);
  EXPECT_EQ(a.direction_unit, b.direction_unit);
  EXPECT_EQ(a.onset_fraction, b.onset_fraction);
  EXPECT_NE(a.direction_unit, c.direction_unit);
  EXPECT_NEAR(a.direction_unit.norm(), 1.0, 1e-12);
  EXPECT_GE(a.onset_fraction, 0.0);
  EXPECT_LT(a.onset_fraction, 1.0);
  // Onsets spread over [1 s, a third of the flight].
  double earliest = 1e9, latest = 0.0;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const double onset = FaultOnsetS(DrawFault(seed), 30.0);
    earliest = std::min(earliest, onset);
    latest = std::max(latest, onset);
  }
  EXPECT_GE(earliest, 1.0);
  EXPECT_LT(earliest, 1.5);
  EXPECT_LE(latest, 10.0);
  EXPECT_GT(latest, 9.5);
}

}  // namespace
}  // namespace aperture::experiments
