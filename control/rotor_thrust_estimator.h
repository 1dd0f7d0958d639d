#pragma once
// Open-loop estimate of the four single-rotor thrusts [N] and of the body torques they produce,
// for the torque feedback eta_hat of the LQR body-rate controller (Faessler thesis G.3, text
// after (G.12)): the commanded thrusts are passed through the asymmetric first-order rotor model
//     f_dot = (f_des - f) / alpha_up    if f_des >= f,
//     f_dot = (f_des - f) / alpha_dwn   otherwise                               (G.7)
// and mapped to torques with (G.1). Rotor-speed feedback would improve it (thesis); none is used.
#include <Eigen/Core>

#include "control/commands.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {

class RotorThrustEstimator {
 public:
  // Starts at hover, m g / 4 per rotor (the usual initial condition of a flying start); call
  // Reset() for a vehicle on the ground. Throws std::invalid_argument for invalid parameters.
  explicit RotorThrustEstimator(const VehicleParameters& vehicle);

  // Throws std::invalid_argument when a thrust is not finite.
  void Reset(const Eigen::Vector4d& thrust_N);

  // Advances (G.7) by dt_s with the command held constant over the step (zero-order hold, as the
  // flight controller applies it). Exact: a first-order lag towards a constant never crosses it,
  // so each rotor stays on one branch, f <- f_des + (f - f_des) exp(-dt / alpha).
  // Throws std::invalid_argument for dt_s <= 0 or non-finite commands.
  void Propagate(const RotorThrustCommand& command, double dt_s);

  const Eigen::Vector4d& thrust_N() const { return thrust_N_; }
  // (G.1) with kappa_i = kappa(f_i / gamma_i) [N m].
  Eigen::Vector3d BodyTorque_B() const;

 private:
  VehicleParameters vehicle_;
  Eigen::Vector4d thrust_N_;
};

}  // namespace aperture::control
