#include "sim/sensors/range_sensor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace aperture::sim {
namespace {

RangeSensorParams NoiselessRange() {
  RangeSensorParams params;
  params.noise_sigma_m = 0.0;
  return params;
}

control::QuadState StateAtHeight(double height_m, const Eigen::Quaterniond& q_WB) {
  control::QuadState state;
  state.p_WB = Eigen::Vector3d(3.0, -1.0, height_m);
  state.q_WB = q_WB;
  return state;
}

TEST(RangeSensorTest, LevelVehicleMeasuresItsHeight) {
  RangeSensor sensor(NoiselessRange());
  const auto reading = sensor.Measure(StateAtHeight(2.5, Eigen::Quaterniond::Identity()));
  EXPECT_TRUE(reading.valid);
  EXPECT_NEAR(reading.range_m, 2.5, 1e-12);
}

TEST(RangeSensorTest, TiltedRayMeasuresHeightOverCosineOfTilt) {
  RangeSensor sensor(NoiselessRange());
  const double tilt = 0.4;  // below the 30 deg limit
  for (const Eigen::Vector3d& axis : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, -1, 0),
                                      Eigen::Vector3d(1, 1, 0).normalized()}) {
    // Yaw does not change the tilt of the ray.
    const Eigen::Quaterniond q_WB =
        Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(tilt, axis);
    const auto reading = sensor.Measure(StateAtHeight(2.0, q_WB));
    EXPECT_TRUE(reading.valid);
    EXPECT_NEAR(reading.range_m, 2.0 / std::cos(tilt), 1e-12);
  }
}

TEST(RangeSensorTest, InvalidBeyondTiltLimitRangeLimitsOrUpsideDown) {
  RangeSensor sensor(NoiselessRange());
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  const double limit = sensor.params().max_tilt_rad;
  EXPECT_TRUE(sensor
                  .Measure(StateAtHeight(1.0, Eigen::Quaterniond(Eigen::AngleAxisd(
                                                  limit - 1e-3, Eigen::Vector3d::UnitX()))))
                  .valid);
  EXPECT_FALSE(sensor
                   .Measure(StateAtHeight(1.0, Eigen::Quaterniond(Eigen::AngleAxisd(
                                                   limit + 1e-3, Eigen::Vector3d::UnitX()))))
                   .valid);
  EXPECT_FALSE(sensor
                   .Measure(StateAtHeight(
                       1.0, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()))))
                   .valid);
  EXPECT_FALSE(sensor.Measure(StateAtHeight(0.1, level)).valid);  // below min_range_m = 0.2
  EXPECT_TRUE(sensor.Measure(StateAtHeight(13.9, level)).valid);
  EXPECT_FALSE(sensor.Measure(StateAtHeight(14.1, level)).valid);  // beyond max_range_m = 14
  EXPECT_FALSE(sensor.Measure(StateAtHeight(-1.0, level)).valid);  // under the ground
  // Tilted: 13 m height at 25 deg tilt is 14.34 m of ray, beyond the maximum.
  EXPECT_FALSE(
      sensor
          .Measure(StateAtHeight(13.0, Eigen::Quaterniond(Eigen::AngleAxisd(
                                           25.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()))))
          .valid);
}

TEST(RangeSensorTest, MountOffsetIsRotatedIntoWorld) {
  RangeSensorParams params = NoiselessRange();
  params.p_BS = Eigen::Vector3d(0.1, 0.0, -0.05);
  RangeSensor sensor(params);
  const double pitch = 0.3;  // nose down for +pitch about y_B: the forward sensor drops
  const auto reading = sensor.Measure(
      StateAtHeight(1.0, Eigen::Quaterniond(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))));
  const double sensor_height = 1.0 - 0.1 * std::sin(pitch) - 0.05 * std::cos(pitch);
  ASSERT_TRUE(reading.valid);
  EXPECT_NEAR(reading.range_m, sensor_height / std::cos(pitch), 1e-12);
}

TEST(RangeSensorTest, GroundHeightShiftsTheReading) {
  RangeSensor sensor(NoiselessRange(), RangeWorld{0.5, nullptr, {}});
  const auto reading = sensor.Measure(StateAtHeight(2.5, Eigen::Quaterniond::Identity()));
  ASSERT_TRUE(reading.valid);
  EXPECT_NEAR(reading.range_m, 2.0, 1e-12);
  EXPECT_FALSE(
      sensor.Measure(StateAtHeight(0.4, Eigen::Quaterniond::Identity())).valid);  // below it
}

TEST(RangeSensorTest, SeesSceneObjectsBelowExceptThoseItLooksThrough) {
  // A 0.4 m high box under the vehicle at (3, -1) and a body part around the sensor.
  Scene scene;
  Eigen::Isometry3d T_WBox = Eigen::Isometry3d::Identity();
  T_WBox.translation() = Eigen::Vector3d(3.0, -1.0, 0.2);
  scene.AddObject({"box", Box{Eigen::Vector3d(0.5, 0.5, 0.4)}, Material{}, T_WBox});
  Eigen::Isometry3d T_WPart = Eigen::Isometry3d::Identity();
  T_WPart.translation() = Eigen::Vector3d(3.0, -1.0, 2.0);
  const int part =
      scene.AddObject({"body", Box{Eigen::Vector3d(0.2, 0.2, 0.1)}, Material{}, T_WPart});
  const control::QuadState above_box = StateAtHeight(2.0, Eigen::Quaterniond::Identity());

  RangeSensor sees_part(NoiselessRange(), RangeWorld{0.0, &scene, {}});
  EXPECT_FALSE(sees_part.Measure(above_box).valid);  // 0.05 m to the part: below min_range_m

  RangeSensor sensor(NoiselessRange(), RangeWorld{0.0, &scene, {part}});
  const auto over_box = sensor.Measure(above_box);
  ASSERT_TRUE(over_box.valid);
  EXPECT_NEAR(over_box.range_m, 1.6, 1e-12);
  // Tilted 0.1 rad about x_W: the ray meets the box top 1.6 tan(0.1) = 0.16 m off centre.
  const double tilt = 0.1;
  const auto tilted = sensor.Measure(
      StateAtHeight(2.0, Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()))));
  ASSERT_TRUE(tilted.valid);
  EXPECT_NEAR(tilted.range_m, 1.6 / std::cos(tilt), 1e-12);
  // Beside the box: the ground.
  control::QuadState beside = above_box;
  beside.p_WB.x() += 1.0;
  const auto ground = sensor.Measure(beside);
  ASSERT_TRUE(ground.valid);
  EXPECT_NEAR(ground.range_m, 2.0, 1e-12);
}

TEST(RangeSensorTest, NoiseStdMatchesSigmaAndIsDeterministic) {
  RangeSensorParams params;
  params.noise_sigma_m = 0.02;
  RangeSensor a(params), b(params);
  const int n = 20000;
  double sum = 0.0, sum_sq = 0.0;
  const control::QuadState state = StateAtHeight(5.0, Eigen::Quaterniond::Identity());
  for (int k = 0; k < n; ++k) {
    const auto ra = a.Measure(state), rb = b.Measure(state);
    ASSERT_TRUE(ra.valid);
    EXPECT_EQ(ra.range_m, rb.range_m);
    sum += ra.range_m - 5.0;
    sum_sq += (ra.range_m - 5.0) * (ra.range_m - 5.0);
  }
  const double mean = sum / n, stdev = std::sqrt(sum_sq / n - mean * mean);
  // Sample std of 2e4 draws: 0.5 % relative std, so 5 % is a 10-sigma bound; mean within 5 sigma.
  EXPECT_NEAR(stdev / 0.02, 1.0, 0.05);
  EXPECT_NEAR(mean, 0.0, 5.0 * 0.02 / std::sqrt(n));
}

TEST(RangeSensorTest, UpdateProducesReadingsAtTheSensorRate) {
  RangeSensor sensor(NoiselessRange());  // 100 Hz
  control::QuadState state = StateAtHeight(1.0, Eigen::Quaterniond::Identity());
  int readings = 0;
  for (int k = 1; k <= 1000; ++k) {
    state.t_s = k * 1e-3;
    if (const auto r = sensor.Update(state)) {
      EXPECT_NEAR(r->t_s, state.t_s, 0.0);
      ++readings;
    }
  }
  EXPECT_EQ(readings, 100);
}

TEST(RangeSensorTest, ValidateNamesTheField) {
  RangeSensorParams params;
  params.max_range_m = 0.1;  // below min_range_m
  try {
    RangeSensor sensor(params);
    FAIL() << "max_range_m < min_range_m accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_range_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aperture::sim
