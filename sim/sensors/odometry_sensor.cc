#include "sim/sensors/odometry_sensor.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "control/so3.h"

namespace aperture::sim {

void OdometrySensorParams::Validate() const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("OdometrySensorParams: " + what);
  };
  require(std::isfinite(rate_hz) && rate_hz > 0.0, "rate_hz must be > 0");
  require(std::isfinite(position_sigma_m) && position_sigma_m > 0.0,
          "position_sigma_m must be > 0 (the filter needs a covariance)");
  require(std::isfinite(rotation_sigma_rad) && rotation_sigma_rad > 0.0,
          "rotation_sigma_rad must be > 0 (the filter needs a covariance)");
}

OdometrySensor::OdometrySensor(const OdometrySensorParams& params)
    : params_((params.Validate(), params)), schedule_(params.rate_hz), rng_(params.seed) {}

Eigen::Vector3d OdometrySensor::GaussianVector(double sigma) {
  return Eigen::Vector3d(normal_(rng_), normal_(rng_), normal_(rng_)) * sigma;
}

std::optional<perception::PoseMeasurement> OdometrySensor::Update(const control::QuadState& state) {
  if (!schedule_.Due(state.t_s)) return std::nullopt;
  perception::PoseMeasurement m;
  m.t_s = state.t_s;
  m.p_WX = state.p_WB + GaussianVector(params_.position_sigma_m);
  m.q_WX = (state.q_WB * control::ExpQuaternion(GaussianVector(params_.rotation_sigma_rad)))
               .normalized();
  m.covariance.setZero();
  m.covariance.topLeftCorner<3, 3>().diagonal().setConstant(params_.position_sigma_m *
                                                            params_.position_sigma_m);
  m.covariance.bottomRightCorner<3, 3>().diagonal().setConstant(params_.rotation_sigma_rad *
                                                                params_.rotation_sigma_rad);
  return m;
}

}  // namespace aperture::sim
