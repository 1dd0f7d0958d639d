#include "control/proportional_body_rate_controller.h"

#include <Eigen/Geometry>
#include <stdexcept>

namespace aperture::control {

ProportionalBodyRateController::ProportionalBodyRateController(
    const VehicleParameters& vehicle, const ProportionalBodyRateParameters& params)
    : params_(params) {
  vehicle.Validate();
  if (!params_.rate_gains_per_s.allFinite() || (params_.rate_gains_per_s.array() < 0.0).any()) {
    throw std::invalid_argument(
        "ProportionalBodyRateParameters.rate_gains_per_s must be finite and >= 0");
  }
  inertia_kgm2_ = vehicle.Inertia();
  inertia_times_gain_ = inertia_kgm2_ * params_.rate_gains_per_s.asDiagonal();
}

Eigen::Vector3d ProportionalBodyRateController::ComputeTorque(
    const Eigen::Vector3d& omega_des_B, const Eigen::Vector3d& omega_B) const {
  // Faessler thesis (B.21) / (A.16)
  return inertia_times_gain_ * (omega_des_B - omega_B) + omega_B.cross(inertia_kgm2_ * omega_B);
}

}  // namespace aperture::control
