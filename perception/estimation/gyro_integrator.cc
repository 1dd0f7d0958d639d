#include "perception/estimation/gyro_integrator.h"

#include <string>

#include "control/require.h"
#include "control/so3.h"

namespace aperture::perception {

void GyroIntegrator::Add(const ImuSample& sample) {
  control::RequireFinite(sample.t_s, "ImuSample.t_s");
  control::RequireFinite(sample.omega_B, "ImuSample.omega_B");
  if (!last_) {
    first_t_s_ = sample.t_s;
    last_ = sample;
    return;
  }
  control::Require(sample.t_s > last_->t_s, "ImuSample.t_s", sample.t_s,
                   "must be later than the previous sample's " + std::to_string(last_->t_s) +
                       " s (IMU samples in time order)");
  const double dt_s = sample.t_s - last_->t_s;
  R_B0B_ = R_B0B_ * control::ExpSo3(0.5 * (last_->omega_B + sample.omega_B) * dt_s);
  last_ = sample;
}

std::optional<Eigen::Matrix3d> GyroIntegrator::OrientationAt(double t_s) const {
  if (!last_ || !(t_s >= first_t_s_)) return std::nullopt;
  return R_B0B_ * control::ExpSo3(last_->omega_B * (t_s - last_->t_s));
}

}  // namespace aperture::perception
