#pragma once
// LQR body-rate controller that accounts for the rotor dynamics (Faessler thesis (G.6)-(G.12)).
//
// Design model (G.9): state s = [omega_B; eta_B] (body rates [rad/s], body torques [N m]), input
// eta_des [N m]; (G.6) linearized at omega = 0 and the torque lag (G.8) with the symmetric time
// constant alpha = (alpha_up + alpha_dwn) / 2:
//     A = [0, J^-1; 0, -I/alpha],  B = [0; I/alpha].
// Gains K (3 x 6) from the CARE with Q = diag(state_weights), R = diag(input_weights) (G.10);
// for diagonal J, K has the PD structure of (G.11).
// Control law (G.12):
//     eta_des = K [omega_des - omega_hat; eta_ref - eta_hat] + omega_hat x J omega_hat
//               + J omega_dot_des,   eta_ref = omega_des x J omega_des + J omega_dot_des,
// with eta_hat from RotorThrustEstimator (asymmetric (G.7) applied to the commanded thrusts).
#include <Eigen/Core>

#include "control/care_solver.h"
#include "control/commands.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {

struct LqrBodyRateParameters {
  // Q diagonal {omega_x, omega_y, omega_z, eta_x, eta_y, eta_z} [(N m s)^2 per rad^2; 1 for the
  // torques]. With R = diag(r) the rate gain of (G.11) is exactly k_omega = sqrt(q_omega / r),
  // independent of q_eta (solve the (1,1) entry of the 2 x 2 CARE per axis), and
  // k_eta = sqrt(1 + 2 alpha k_omega / (J r) + q_eta / r) - 1.
  // Default: "LQR with equivalent gains to (b)" (G.6.2): k_omega = J p of the high-gain
  // proportional controller (p_pq = 100, p_r = 20 1/s, see ProportionalBodyRateParameters::
  // HighGain) for the Table A.2 inertia, i.e. q_omega = (J p)^2 = {0.01, 0.01, 0.0016}, and no
  // torque weight. Then k_eta = 1.19 (roll/pitch), 0.33 (yaw), giving the rate loop the damping
  // (1 + k_eta) / (2 sqrt(alpha p)) = 0.79 where the high-gain P controller has 0.36. Use
  // FromEquivalentRateGains for another vehicle.
  Eigen::Matrix<double, 6, 1> state_weights =
      (Eigen::Matrix<double, 6, 1>() << 0.01, 0.01, 0.0016, 0.0, 0.0, 0.0).finished();
  // R diagonal; the thesis uses R = I (G.10).
  Eigen::Vector3d input_weights = Eigen::Vector3d::Ones();

  // Weights whose LQR rate gains equal J p of a proportional controller with gains p [1/s]
  // (R = I, q_omega = (J_ii p_i)^2), optionally with torque weights q_eta.
  static LqrBodyRateParameters FromEquivalentRateGains(
      const Eigen::Vector3d& inertia_diag_kgm2, const Eigen::Vector3d& rate_gains_per_s,
      const Eigen::Vector3d& torque_weights = Eigen::Vector3d::Zero());
};

// The linear design model (G.9).
struct BodyRateLinearModel {
  Eigen::Matrix<double, 6, 6> A;
  Eigen::Matrix<double, 6, 3> B;
  double time_constant_s = 0.0;  // alpha = (alpha_up + alpha_dwn) / 2
};
BodyRateLinearModel BuildBodyRateLinearModel(const VehicleParameters& vehicle);

class LqrBodyRateController {
 public:
  // Solves the CARE once. Throws std::invalid_argument for invalid vehicle parameters, weights
  // that are negative / non-finite (input weights must be > 0), or weights for which the CARE has
  // no stabilizing solution (a zero rate weight leaves the rate integrators unobserved).
  explicit LqrBodyRateController(const VehicleParameters& vehicle,
                                 const LqrBodyRateParameters& params = {});

  // (G.12): desired body torque [N m] from the command's omega_des_B and omega_dot_des_B, the
  // estimated body rates omega_B [rad/s] and the estimated body torques torque_estimate_B [N m].
  Eigen::Vector3d ComputeTorque(const ThrustRatesCommand& command, const Eigen::Vector3d& omega_B,
                                const Eigen::Vector3d& torque_estimate_B) const;

  const Eigen::Matrix<double, 3, 6>& gain() const { return gain_; }
  const CareResult& care_result() const { return care_result_; }
  const BodyRateLinearModel& model() const { return model_; }

 private:
  Eigen::Matrix3d inertia_kgm2_;
  BodyRateLinearModel model_;
  CareResult care_result_;
  Eigen::Matrix<double, 3, 6> gain_;
};

}  // namespace aperture::control
