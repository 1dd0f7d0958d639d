#include "perception/estimation/pose_imu_filter_params_io.h"

#include <stdexcept>
#include <string>

namespace aperture::perception {

void LoadParams(config::ParamReader& reader, PoseImuFilterParams* params) {
  reader.Read("accel_noise_density", &params->accel_noise_density);
  reader.Read("gyro_noise_density", &params->gyro_noise_density);
  reader.Read("accel_bias_random_walk", &params->accel_bias_random_walk);
  reader.Read("gyro_bias_random_walk", &params->gyro_bias_random_walk);
  reader.Read("gravity_mps2", &params->gravity_mps2);
  reader.Read("initial_position_sigma_m", &params->initial_position_sigma_m);
  reader.Read("initial_velocity_sigma_mps", &params->initial_velocity_sigma_mps);
  reader.Read("initial_attitude_sigma_rad", &params->initial_attitude_sigma_rad);
  reader.Read("initial_accel_bias_sigma_mps2", &params->initial_accel_bias_sigma_mps2);
  reader.Read("initial_gyro_bias_sigma_radps", &params->initial_gyro_bias_sigma_radps);
  reader.Read("history_duration_s", &params->history_duration_s);
  reader.Read("mahalanobis_gate", &params->mahalanobis_gate);
  reader.RejectUnknownKeys();
  try {
    params->Validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(reader.Where("") + ": " + e.what());
  }
}

}  // namespace aperture::perception
