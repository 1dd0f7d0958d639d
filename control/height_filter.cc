#include "control/height_filter.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::control {
void HeightFilterParams::Validate() const {
  RequirePositive(accel_noise_sigma_mps2, "HeightFilterParams.accel_noise_sigma_mps2");
  RequirePositive(range_noise_sigma_m, "HeightFilterParams.range_noise_sigma_m");
  RequirePositive(range_period_s, "HeightFilterParams.range_period_s");
  RequirePositive(gravity_mps2, "HeightFilterParams.gravity_mps2");
  if (gain_K && !gain_K->allFinite()) {
    throw std::invalid_argument("HeightFilterParams::gain_K must be finite");
  }
}

HeightFilter::HeightFilter(const HeightFilterParams& params) : params_(params) {
  params_.Validate();
  gain_K_ = params_.gain_K ? *params_.gain_K
                           : ComputeSteadyStateGain(params_.range_period_s,
                                                    params_.accel_noise_sigma_mps2,
                                                    params_.range_noise_sigma_m);
}

Eigen::Vector2d HeightFilter::ComputeSteadyStateGain(double dt, double accel_sigma,
                                                     double range_sigma) {
  if (!(dt > 0.0) || !(accel_sigma > 0.0) || !(range_sigma > 0.0)) {
    throw std::invalid_argument(
        "HeightFilter::ComputeSteadyStateGain: range period and noise sigmas must be > 0");
  }
  Eigen::Matrix2d F;
  F << 1.0, dt, 0.0, 1.0;
  const Eigen::Vector2d G(0.5 * dt * dt, dt);
  const Eigen::Matrix2d Q = accel_sigma * accel_sigma * G * G.transpose();
  const double R = range_sigma * range_sigma;
  Eigen::Matrix2d P = Eigen::Matrix2d::Identity();
  Eigen::Vector2d K = Eigen::Vector2d::Zero();
  // The Riccati recursion of a detectable, stabilizable 2-state system converges geometrically;
  // stop when the gain no longer changes in double precision terms.
  for (int i = 0; i < 100000; ++i) {
    const Eigen::Matrix2d P_prior = F * P * F.transpose() + Q;
    const Eigen::Vector2d K_new = P_prior.col(0) / (P_prior(0, 0) + R);
    P = P_prior - K_new * P_prior.row(0);
    const bool converged = (K_new - K).norm() <= 1e-14 * K_new.norm();
    K = K_new;
    if (converged) break;
  }
  return K;
}

double HeightFilter::VerticalAcceleration(const Eigen::Quaterniond& q_WB,
                                          const Eigen::Vector3d& specific_force_B,
                                          double gravity_mps2) {
  return (q_WB * specific_force_B).z() - gravity_mps2;
}

std::optional<double> HeightFilter::HeightFromRange(double range_m,
                                                    const Eigen::Quaterniond& q_WB) {
  const double cos_tilt = (q_WB * Eigen::Vector3d::UnitZ()).z();
  if (!(cos_tilt > 0.0) || !std::isfinite(range_m)) return std::nullopt;
  return range_m * cos_tilt;
}

void HeightFilter::Initialize(double z_m, double z_dot_mps) {
  if (!std::isfinite(z_m) || !std::isfinite(z_dot_mps)) {
    throw std::invalid_argument("HeightFilter::Initialize: z_m and z_dot_mps must be finite");
  }
  estimate_ = HeightEstimate{z_m, z_dot_mps, 0.0};
  initialized_ = true;
}

void HeightFilter::Predict(double dt_s, double a_z_mps2) {
  if (!initialized_) throw std::logic_error("HeightFilter::Predict before Initialize()");
  if (!(dt_s > 0.0) || !std::isfinite(dt_s) || !std::isfinite(a_z_mps2)) {
    throw std::invalid_argument("HeightFilter::Predict: dt_s = " + std::to_string(dt_s) +
                                " must be > 0 and a_z finite");
  }
  // (B.27)
  estimate_.z_m += dt_s * estimate_.z_dot_mps + 0.5 * dt_s * dt_s * a_z_mps2;
  estimate_.z_dot_mps += dt_s * a_z_mps2;
  estimate_.time_since_init_s += dt_s;
}

void HeightFilter::Update(double z_meas_m) {
  if (!initialized_) throw std::logic_error("HeightFilter::Update before Initialize()");
  if (!std::isfinite(z_meas_m)) {
    throw std::invalid_argument("HeightFilter::Update: non-finite height measurement");
  }
  const double innovation = z_meas_m - estimate_.z_m;  // (B.28)
  estimate_.z_m += gain_K_(0) * innovation;
  estimate_.z_dot_mps += gain_K_(1) * innovation;
}

}  // namespace aperture::control
