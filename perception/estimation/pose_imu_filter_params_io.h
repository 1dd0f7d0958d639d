#pragma once
// Configuration description (Serialize, config/param_archive.h) of PoseImuFilterParams: the
// loader LoadParams(reader, &params) (config/yaml_read_archive.h) and the dump
// config::DumpParams(params). Keys are the field names (they carry their units); absent keys keep
// the in-class defaults; unknown keys are rejected with the location and the list of known keys;
// the loaded struct is validated (errors name the location and the field).
//
//   pose_imu_filter:
//     accel_noise_density: 3.9e-3       # m/s^2/sqrt(Hz)
//     gyro_noise_density: 8.7e-5        # rad/s/sqrt(Hz)
//     accel_bias_random_walk: 3.0e-3    # m/s^3/sqrt(Hz)
//     gyro_bias_random_walk: 2.0e-5     # rad/s^2/sqrt(Hz)
//     gravity_mps2: 9.81
//     initial_position_sigma_m: 0.5
//     initial_velocity_sigma_mps: 0.5
//     initial_attitude_sigma_rad: 0.1
//     initial_accel_bias_sigma_mps2: 0.1
//     initial_gyro_bias_sigma_radps: 0.01
//     history_duration_s: 0.5
//     mahalanobis_gate: 22.46           # .inf disables gating
//     height_mahalanobis_gate: 10.83    # chi-square(1); .inf disables gating
#include "config/yaml_read_archive.h"
#include "perception/estimation/pose_imu_filter.h"

namespace aperture::perception {

template <typename Archive>
void Serialize(Archive* a, PoseImuFilterParams* p) {
  a->Visit(APERTURE_NVP(p, accel_noise_density));
  a->Visit(APERTURE_NVP(p, gyro_noise_density));
  a->Visit(APERTURE_NVP(p, accel_bias_random_walk));
  a->Visit(APERTURE_NVP(p, gyro_bias_random_walk));
  a->Visit(APERTURE_NVP(p, gravity_mps2));
  a->Visit(APERTURE_NVP(p, initial_position_sigma_m));
  a->Visit(APERTURE_NVP(p, initial_velocity_sigma_mps));
  a->Visit(APERTURE_NVP(p, initial_attitude_sigma_rad));
  a->Visit(APERTURE_NVP(p, initial_accel_bias_sigma_mps2));
  a->Visit(APERTURE_NVP(p, initial_gyro_bias_sigma_radps));
  a->Visit(APERTURE_NVP(p, history_duration_s));
  a->VisitLimit(APERTURE_NVP(p, mahalanobis_gate));
  a->VisitLimit(APERTURE_NVP(p, height_mahalanobis_gate));
}

}  // namespace aperture::perception
