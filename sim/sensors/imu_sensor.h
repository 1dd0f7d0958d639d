#pragma once
// Simulated IMU (frame = B, DESIGN.md). Measures what a real strap-down IMU at the centre of mass
// measures: the specific force (all non-gravitational forces over mass: thrust + rotor drag, not
// gravity; QuadrotorDynamics::SpecificForce_B) and the body rates, each corrupted by
//   y_k = x(t_k) + b(t_k) + n_k,   n_k ~ N(0, sigma_c^2 / dt)        (white noise, density sigma_c)
//   b(t_{k+1}) = b(t_k) + w_k,     w_k ~ N(0, sigma_b^2 dt)          (bias random walk, sigma_b)
// with dt = 1 / rate_hz: the exact discretization of continuous-time white noise of density
// sigma_c [unit/sqrt(Hz)] averaged over a sample and of a Wiener bias process of density sigma_b
// [unit/s/sqrt(Hz)] (the Kalibr / OpenVINS IMU noise model). Samples are delivered latency_s after
// they are taken. Deterministic for a given seed (std::mt19937_64).
#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "perception/imu_noise_params.h"
#include "perception/sensor_data.h"
#include "sim/sensors/sample_schedule.h"

namespace aperture::sim {

// Noise densities and bias random walks: perception::ImuNoiseParams (the defaults the filter
// expects, an MPU-6000-class MEMS IMU); the rest is how this IMU samples and delivers.
struct ImuSensorParams : perception::ImuNoiseParams {
  double rate_hz = 500.0;         // output rate; the simulator must step at least this fast
  // Delivery delay [s] (bus transfer + driver). 0 = delivered in the step it is taken.
  double latency_s = 0.002;
  // false: a sample keeps its measurement time t_s and arrives latency_s later (a synchronized
  // driver). true: it is stamped with its arrival time, so the data are latency_s older than the
  // stamp (a driver that stamps on reception; unmodelled latency for the estimator).
  bool stamp_at_delivery = false;
  Eigen::Vector3d accel_bias_initial_B = Eigen::Vector3d::Zero();  // [m/s^2]
  Eigen::Vector3d gyro_bias_initial_B = Eigen::Vector3d::Zero();   // [rad/s]
  std::uint64_t seed = 1;

  // Throws std::invalid_argument naming the field: rate_hz <= 0, latency_s < 0, negative
  // densities, non-finite values.
  void Validate() const;
};

class ImuSensor {
 public:
  explicit ImuSensor(const ImuSensorParams& params);

  // Call once per simulation step with the true specific force and body rates at simulator time
  // t_s (non-decreasing). Takes a sample when one is due and returns every sample whose delivery
  // time (t_sample + latency_s) is <= t_s, oldest first (usually zero or one).
  std::vector<perception::ImuSample> Update(double t_s, const Eigen::Vector3d& specific_force_B,
                                            const Eigen::Vector3d& omega_B);

  // Current true biases (ground truth for estimator tests).
  const Eigen::Vector3d& accel_bias_B() const { return accel_bias_B_; }
  const Eigen::Vector3d& gyro_bias_B() const { return gyro_bias_B_; }
  const ImuSensorParams& params() const { return params_; }

 private:
  Eigen::Vector3d GaussianVector(double sigma);

  ImuSensorParams params_;
  SampleSchedule schedule_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  Eigen::Vector3d accel_bias_B_, gyro_bias_B_;
  std::deque<perception::ImuSample> in_flight_;  // taken, not yet delivered
};

}  // namespace aperture::sim
