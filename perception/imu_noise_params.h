#pragma once
// The continuous-time IMU noise model, one set of numbers for the simulated IMU
// (sim/sensors/imu_sensor.h draws from it) and the filter that expects it
// (perception/estimation/pose_imu_filter.h propagates it), so the two agree by default:
//   measurement = truth + bias + white noise of density sigma_c   [unit/sqrt(Hz)]
//   d(bias)/dt  = white noise of density sigma_b                  [unit/s/sqrt(Hz)]
// (the Kalibr / OpenVINS IMU noise model). Frame B (the IMU frame, DESIGN.md).
#include <string>

namespace aperture::perception {

// Defaults: an MPU-6000/MPU-9250-class MEMS IMU as on small research quadrotors. White-noise
// densities from the InvenSense MPU-6000 datasheet (gyro 0.005 deg/s/sqrt(Hz), accelerometer
// 400 ug/sqrt(Hz)); bias random walks, which MEMS datasheets do not list, are the order of
// magnitude used for such IMUs in VIO calibrations (Kalibr/EuRoC-style values).
struct ImuNoiseParams {
  double accel_noise_density = 400e-6 * 9.81;                    // [m/s^2/sqrt(Hz)] = 3.9e-3
  double gyro_noise_density = 0.005 * 3.14159265358979 / 180.0;  // [rad/s/sqrt(Hz)] = 8.7e-5
  double accel_bias_random_walk = 3.0e-3;                        // [m/s^3/sqrt(Hz)]
  double gyro_bias_random_walk = 2.0e-5;                         // [rad/s^2/sqrt(Hz)]

  // Throws std::invalid_argument naming "<owner>.<field>" for a negative or non-finite entry
  // (0 is allowed: a noise-free IMU).
  void ValidateNoise(const std::string& owner) const;
  // Multiplies both densities and both bias random walks by factor (a noisier IMU of the same
  // kind: `aperture bench faults`' imu_noise, the gap bench's per-trial IMU noise scale).
  void ScaleNoise(double factor);
};

}  // namespace aperture::perception
