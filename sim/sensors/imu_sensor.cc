#include "sim/sensors/imu_sensor.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::sim {
namespace {

const ImuSensorParams& Validated(const ImuSensorParams& params) {
  params.Validate();
  return params;
}

}  // namespace

void ImuSensorParams::Validate() const {
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    throw std::invalid_argument("ImuSensorParams.rate_hz must be > 0, got " + std::to_string(rate_hz));
  }
  control::RequireNonNegative(latency_s, "ImuSensorParams.latency_s");
  ValidateNoise("ImuSensorParams");
  if (!(accel_bias_initial_B.allFinite() && gyro_bias_initial_B.allFinite())) {
    throw std::invalid_argument("ImuSensorParams: initial biases must be finite");
  }
}

ImuSensor::ImuSensor(const ImuSensorParams& params)
    : params_(Validated(params)),
      schedule_(params_.rate_hz),
      rng_(params.seed),
      accel_bias_B_(params.accel_bias_initial_B),
      gyro_bias_B_(params.gyro_bias_initial_B) {}

Eigen::Vector3d ImuSensor::GaussianVector(double sigma) {
  // Drawn even when sigma == 0 so the random stream, and thus every other channel, does not
  // depend on which noise terms are enabled.
  Eigen::Vector3d n;
  for (int i = 0; i < 3; ++i) n[i] = sigma * normal_(rng_);
  return n;
}

std::vector<perception::ImuSample> ImuSensor::Update(double t_s,
                                                     const Eigen::Vector3d& specific_force_B,
                                                     const Eigen::Vector3d& omega_B) {
  if (!(std::isfinite(t_s) && specific_force_B.allFinite() && omega_B.allFinite())) {
    throw std::invalid_argument("ImuSensor::Update: time and true signals must be finite");
  }
  if (schedule_.Due(t_s)) {
    const double dt_s = schedule_.period_s();
    const double white_scale = 1.0 / std::sqrt(dt_s);  // sigma_d = sigma_c * sqrt(rate)
    perception::ImuSample sample;
    sample.t_s = t_s;
    sample.specific_force_B =
        specific_force_B + accel_bias_B_ + GaussianVector(params_.accel_noise_density * white_scale);
    sample.omega_B = omega_B + gyro_bias_B_ + GaussianVector(params_.gyro_noise_density * white_scale);
    in_flight_.push_back(sample);
    const double walk_scale = std::sqrt(dt_s);  // Wiener increment over one sample period
    accel_bias_B_ += GaussianVector(params_.accel_bias_random_walk * walk_scale);
    gyro_bias_B_ += GaussianVector(params_.gyro_bias_random_walk * walk_scale);
  }
  std::vector<perception::ImuSample> delivered;
  // A small tolerance so that latency = k steps is not lost to rounding of the simulator clock.
  const double tolerance_s = 1e-9;
  while (!in_flight_.empty() && in_flight_.front().t_s + params_.latency_s <= t_s + tolerance_s) {
    delivered.push_back(in_flight_.front());
    if (params_.stamp_at_delivery) delivered.back().t_s = t_s;
    in_flight_.pop_front();
  }
  return delivered;
}

}  // namespace aperture::sim
