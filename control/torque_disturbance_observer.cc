#include "control/torque_disturbance_observer.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace aperture::control {

TorqueDisturbanceObserver::TorqueDisturbanceObserver(const Eigen::Vector3d& inertia_diag_kgm2,
                                                     double time_constant_s)
    : inertia_diag_kgm2_(inertia_diag_kgm2), time_constant_s_(time_constant_s) {
  if (!(std::isfinite(time_constant_s) && time_constant_s > 0.0)) {
    throw std::invalid_argument(
        "TorqueDisturbanceObserver: the time constant must be positive and finite [s]");
  }
  if (!inertia_diag_kgm2.allFinite() || (inertia_diag_kgm2.array() <= 0.0).any()) {
    throw std::invalid_argument(
        "TorqueDisturbanceObserver: the inertia must be positive and finite [kg m^2]");
  }
}

void TorqueDisturbanceObserver::Update(const Eigen::Vector3d& omega_B,
                                       const Eigen::Vector3d& eta_hat_B, double dt_s) {
  if (!omega_B.allFinite() || !eta_hat_B.allFinite()) {
    throw std::invalid_argument("TorqueDisturbanceObserver::Update: omega_B and eta_hat_B must "
                                "be finite");
  }
  if (has_previous_) {
    if (!(std::isfinite(dt_s) && dt_s > 0.0)) {
      throw std::invalid_argument("TorqueDisturbanceObserver::Update: dt_s must be > 0");
    }
    const Eigen::Vector3d& J = inertia_diag_kgm2_;
    const Eigen::Vector3d gyroscopic_B =
        previous_omega_B_.cross(J.cwiseProduct(previous_omega_B_));
    const Eigen::Vector3d eta_mean_B = 0.5 * (previous_eta_hat_B_ + eta_hat_B);
    const Eigen::Vector3d omega_pred_B =
        previous_omega_B_ +
        dt_s * (eta_mean_B + disturbance_B_ - gyroscopic_B).cwiseQuotient(J);
    disturbance_B_ += J.cwiseProduct(omega_B - omega_pred_B) / time_constant_s_;
  }
  has_previous_ = true;
  previous_omega_B_ = omega_B;
  previous_eta_hat_B_ = eta_hat_B;
}

void TorqueDisturbanceObserver::Reset() {
  has_previous_ = false;
  disturbance_B_.setZero();
}

}  // namespace aperture::control
