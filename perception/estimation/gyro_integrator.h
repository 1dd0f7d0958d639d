#pragma once
// GyroIntegrator: the body's orientation relative to its first gyro sample, R_B0B(t), from the
// gyroscope rates of a stream of ImuSamples (a bag's IMU topic), for front ends that derotate
// images between frames (ts2p). Trapezoidal rule on the body rates between samples,
// R_B0B(t_i) = R_B0B(t_{i-1}) Exp((omega_{i-1} + omega_i) / 2 * (t_i - t_{i-1})) — exact for a
// rate linear in time about a fixed axis; between the last sample and a later query time the
// last rate is held, and so it is back to a query time a little before the last sample (a bag's
// IMU header stamps may run ahead of the frame that follows them). Gyro bias and the accelerometer
// are ignored (a few frames apart, a bias of 0.01 rad/s at 30 Hz adds ~0.02 deg per frame).
//
//   GyroIntegrator gyro;
//   for (const ImuSample& s : frame.imu) gyro.Add(s);
//   if (auto R_B0B = gyro.OrientationAt(frame.t_s)) ...  // nullopt before the first sample
#include <Eigen/Core>
#include <optional>

#include "perception/sensor_data.h"

namespace aperture::perception {

class GyroIntegrator {
 public:
  // Throws std::invalid_argument naming the field when the sample is not finite or not later
  // than the previous one.
  void Add(const ImuSample& sample);

  // R_B0B at t_s: R_B0B at the last sample times Exp(omega_last (t_s - t_last)); nullopt before
  // any sample or when t_s precedes the first sample.
  std::optional<Eigen::Matrix3d> OrientationAt(double t_s) const;


 private:
  double first_t_s_ = 0.0;
  std::optional<ImuSample> last_;
  Eigen::Matrix3d R_B0B_ = Eigen::Matrix3d::Identity();  // at last_->t_s
};

}  // namespace aperture::perception
