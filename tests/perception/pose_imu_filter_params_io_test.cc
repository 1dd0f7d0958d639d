#include "perception/estimation/pose_imu_filter_params_io.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "perception/gap/gap_detector_params_io.h"
#include "tests/support/message_of.h"
#include "tests/support/param_round_trip.h"

namespace aperture::perception {
namespace {

PoseImuFilterParams LoadFilterParams(const std::string& yaml) {
  config::ParamReader reader(YAML::Load(yaml), "filter.yaml");
  PoseImuFilterParams params;
  LoadParams(reader, &params);
  return params;
}

std::string FilterParamsErrorOf(const std::string& yaml) {
  return test_support::MessageOf([&] { LoadFilterParams(yaml); });
}

TEST(PoseImuFilterParamsIoTest, LoadsGivenKeysAndKeepsDefaults) {
  const PoseImuFilterParams params = LoadFilterParams(R"(
accel_noise_density: 0.01
gyro_bias_random_walk: 1.0e-4
history_duration_s: 0.2
mahalanobis_gate: .inf
)");
  EXPECT_DOUBLE_EQ(params.accel_noise_density, 0.01);
  EXPECT_DOUBLE_EQ(params.gyro_bias_random_walk, 1.0e-4);
  EXPECT_DOUBLE_EQ(params.history_duration_s, 0.2);
  EXPECT_TRUE(std::isinf(params.mahalanobis_gate));
  EXPECT_DOUBLE_EQ(params.gyro_noise_density, PoseImuFilterParams{}.gyro_noise_density);
  EXPECT_DOUBLE_EQ(params.initial_position_sigma_m, PoseImuFilterParams{}.initial_position_sigma_m);
}

TEST(PoseImuFilterParamsIoTest, RejectsUnknownKeysAndInvalidValuesNamingThem) {
  const std::string unknown = FilterParamsErrorOf("accel_noise_densty: 0.01\n");
  EXPECT_NE(unknown.find("accel_noise_densty"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("filter.yaml"), std::string::npos) << unknown;
  const std::string invalid = FilterParamsErrorOf("history_duration_s: -1\n");
  EXPECT_NE(invalid.find("history_duration_s"), std::string::npos) << invalid;
  EXPECT_NE(invalid.find("filter.yaml"), std::string::npos) << invalid;
}

TEST(PoseImuFilterParamsIo, RoundTripsThroughItsDump) {
  test_support::ExpectRoundTrip(PoseImuFilterParams{});
}

TEST(GapDetectorParamsIo, RoundTripsThroughItsDumpAndValidates) {
  test_support::ExpectRoundTrip(GapDetectorParams{});
  config::ParamReader reader(YAML::Load("{canny_low: -4}"), "detector.yaml");
  GapDetectorParams params;
  EXPECT_THROW(LoadParams(reader, &params), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
