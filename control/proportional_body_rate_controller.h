#pragma once
// Proportional body-rate controller with feedback linearization, the baseline of the LQR
// (Faessler thesis (A.16), (B.21)):
//     tau_des = J P (omega_des - omega_hat) + omega_hat x J omega_hat,   P = diag(p_pq, p_pq, p_r).
// Inputs in B [rad/s], output body torque in B [N m] for the Mixer.
#include <Eigen/Core>

#include "control/vehicle_parameters.h"

namespace aperture::control {

struct ProportionalBodyRateParameters {
  // Rate gains {p_pq, p_pq, p_r} [1/s]; default: the low-gain controller (a) of Table G.1, whose
  // values are Table A.2's p_pq = 33.3, p_r = 6.7.
  Eigen::Vector3d rate_gains_per_s{33.3, 33.3, 6.7};

  static ProportionalBodyRateParameters LowGain() { return {}; }
  // High-gain controller (b) of Table G.1. The thesis does not list its gains; we take three times
  // Table A.2 (p_pq = 100, p_r = 20). With the mean rotor lag alpha = 19 ms the rate loop
  // alpha s^2 + s + p then has damping 1 / (2 sqrt(alpha p)) = 0.36 instead of 0.63: the better
  // tracking and slower settling after a disturbance that Table G.1 reports for (b).
  static ProportionalBodyRateParameters HighGain() { return {Eigen::Vector3d(100.0, 100.0, 20.0)}; }
};

class ProportionalBodyRateController {
 public:
  // Throws std::invalid_argument for invalid vehicle parameters or negative / non-finite gains.
  explicit ProportionalBodyRateController(const VehicleParameters& vehicle,
                                          const ProportionalBodyRateParameters& params = {});

  // (B.21): desired body torque [N m] from desired and estimated body rates [rad/s].
  Eigen::Vector3d ComputeTorque(const Eigen::Vector3d& omega_des_B,
                                const Eigen::Vector3d& omega_B) const;

  const ProportionalBodyRateParameters& params() const { return params_; }

 private:
  Eigen::Matrix3d inertia_kgm2_;
  Eigen::Matrix3d inertia_times_gain_;  // J P
  ProportionalBodyRateParameters params_;
};

}  // namespace aperture::control
