#include "control/lqr_body_rate_controller.h"

#include <Eigen/Geometry>
#include <sstream>
#include <stdexcept>

namespace aperture::control {

LqrBodyRateParameters LqrBodyRateParameters::FromEquivalentRateGains(
    const Eigen::Vector3d& inertia_diag_kgm2, const Eigen::Vector3d& rate_gains_per_s,
    const Eigen::Vector3d& torque_weights) {
  LqrBodyRateParameters params;
  params.state_weights << inertia_diag_kgm2.cwiseProduct(rate_gains_per_s).array().square(),
      torque_weights;
  params.input_weights.setOnes();
  return params;
}

BodyRateLinearModel BuildBodyRateLinearModel(const VehicleParameters& vehicle) {
  BodyRateLinearModel model;
  model.time_constant_s =
      0.5 * (vehicle.rotor.time_constant_up_s + vehicle.rotor.time_constant_down_s);
  const double inv_alpha = 1.0 / model.time_constant_s;
  // Faessler thesis (G.9)
  model.A.setZero();
  model.A.topRightCorner<3, 3>() = vehicle.inertia_diag_kgm2.cwiseInverse().asDiagonal();
  model.A.bottomRightCorner<3, 3>() = -inv_alpha * Eigen::Matrix3d::Identity();
  model.B.setZero();
  model.B.bottomRows<3>() = inv_alpha * Eigen::Matrix3d::Identity();
  return model;
}

LqrBodyRateController::LqrBodyRateController(const VehicleParameters& vehicle,
                                             const LqrBodyRateParameters& params) {
  vehicle.Validate();
  if (!params.state_weights.allFinite() || (params.state_weights.array() < 0.0).any()) {
    throw std::invalid_argument("LqrBodyRateParameters.state_weights must be finite and >= 0");
  }
  if (!params.input_weights.allFinite() || (params.input_weights.array() <= 0.0).any()) {
    throw std::invalid_argument("LqrBodyRateParameters.input_weights must be finite and > 0");
  }
  inertia_kgm2_ = vehicle.Inertia();
  model_ = BuildBodyRateLinearModel(vehicle);
  const Eigen::MatrixXd Q = params.state_weights.asDiagonal();
  const Eigen::MatrixXd R = params.input_weights.asDiagonal();
  care_result_ = SolveContinuousAlgebraicRiccati(model_.A, model_.B, Q, R);
  if (!care_result_.ok()) {
    std::ostringstream message;
    message << "LqrBodyRateParameters: no stabilizing LQR gain for state_weights ["
            << params.state_weights.transpose() << "] (" << care_result_
            << "); give every body rate a weight > 0";
    throw std::invalid_argument(message.str());
  }
  gain_ = care_result_.K;
}

Eigen::Vector3d LqrBodyRateController::ComputeTorque(
    const ThrustRatesCommand& command, const Eigen::Vector3d& omega_B,
    const Eigen::Vector3d& torque_estimate_B) const {
  const Eigen::Vector3d& omega_des = command.omega_des_B;
  const Eigen::Vector3d feed_forward = inertia_kgm2_ * command.omega_dot_des_B;
  const Eigen::Vector3d torque_ref = omega_des.cross(inertia_kgm2_ * omega_des) + feed_forward;
  Eigen::Matrix<double, 6, 1> error;
  error << omega_des - omega_B, torque_ref - torque_estimate_B;
  // Faessler thesis (G.12)
  return gain_ * error + omega_B.cross(inertia_kgm2_ * omega_B) + feed_forward;
}

}  // namespace aperture::control
