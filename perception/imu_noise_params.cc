#include "perception/imu_noise_params.h"

#include "control/require.h"

namespace aperture::perception {

void ImuNoiseParams::ValidateNoise(const std::string& owner) const {
  control::RequireNonNegative(accel_noise_density, owner + ".accel_noise_density");
  control::RequireNonNegative(gyro_noise_density, owner + ".gyro_noise_density");
  control::RequireNonNegative(accel_bias_random_walk, owner + ".accel_bias_random_walk");
  control::RequireNonNegative(gyro_bias_random_walk, owner + ".gyro_bias_random_walk");
}

void ImuNoiseParams::ScaleNoise(double factor) {
  accel_noise_density *= factor;
  gyro_noise_density *= factor;
  accel_bias_random_walk *= factor;
  gyro_bias_random_walk *= factor;
}

}  // namespace aperture::perception
