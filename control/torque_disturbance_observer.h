#pragma once
// Estimate of the body torque that the flight controller's model does not explain (beyond the
// Faessler thesis, whose LQR (G.12) trusts the modelled torque eta_hat): a weak or damaged rotor,
// a thrust or torque map that is off, an off-centre payload. The body-rate law subtracts it, which
// gives the rate loop integral action against constant disturbances.
//
// Rigid body (G.6) with the disturbance d_B: J omega_dot = eta + d_B - omega x J omega. Each step
// predicts the gyro rates from the previous ones with the modelled torque (the mean of eta_hat at
// both ends of the step) and the current estimate, and moves the estimate by the prediction error:
//     omega_pred = omega_prev + dt J^-1 (eta_mean + d_hat - omega_prev x J omega_prev)
//     d_hat     += J (omega - omega_pred) / tau
// i.e. a first-order low-pass of time constant tau of the torque residual
// J (omega - omega_prev) / dt - (eta_mean - omega_prev x J omega_prev), without differentiating
// the gyro. Gyro noise enters as J sigma_omega / sqrt(dt tau) (a few 1e-4 N m at 1 kHz here).
#include <Eigen/Core>

namespace aperture::control {

class TorqueDisturbanceObserver {
 public:
  // Throws std::invalid_argument for a non-positive or non-finite time constant or inertia.
  TorqueDisturbanceObserver(const Eigen::Vector3d& inertia_diag_kgm2, double time_constant_s);

  // The gyro rates omega_B [rad/s] at this step and the modelled body torque eta_hat_B [N m]
  // acting from now; dt_s [s] since the previous Update (ignored on the first one, which only
  // records). Throws std::invalid_argument for non-finite inputs or dt_s <= 0 after the first.
  void Update(const Eigen::Vector3d& omega_B, const Eigen::Vector3d& eta_hat_B, double dt_s);
  // Forgets the estimate and the previous step (e.g. on the ground, motors stopped).
  void Reset();

  const Eigen::Vector3d& disturbance_B() const { return disturbance_B_; }  // d_hat [N m]

 private:
  Eigen::Vector3d inertia_diag_kgm2_;
  double time_constant_s_;
  bool has_previous_ = false;
  Eigen::Vector3d previous_omega_B_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d previous_eta_hat_B_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d disturbance_B_ = Eigen::Vector3d::Zero();
};

}  // namespace aperture::control
