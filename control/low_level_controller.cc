#include "control/low_level_controller.h"

#include <cmath>
#include <stdexcept>

namespace aperture::control {

LowLevelController::LowLevelController(const VehicleParameters& vehicle,
                                       const LowLevelControllerParameters& params)
    : vehicle_(vehicle),
      params_((params.Validate(), params)),
      lqr_(vehicle, params.lqr),
      proportional_(vehicle, params.proportional),
      mixer_(vehicle, params.mixer),
      estimator_(vehicle) {
  if (params.torque_observer_time_constant_s > 0.0) {
    observer_.emplace(vehicle.inertia_diag_kgm2, params.torque_observer_time_constant_s);
  }
}

void LowLevelController::ResetThrustEstimate(const Eigen::Vector4d& thrust_N) {
  estimator_.Reset(thrust_N);
  if (observer_) observer_->Reset();
}

LowLevelOutput LowLevelController::Step(const ThrustRatesCommand& command,
                                        const Eigen::Vector3d& omega_B, double dt_s) {
  if (!omega_B.allFinite() || !command.omega_des_B.allFinite() ||
      !command.omega_dot_des_B.allFinite() || !std::isfinite(command.collective_thrust_mps2)) {
    throw std::invalid_argument(
        "LowLevelController::Step: command and omega_B must be finite (check the estimator and "
        "the high-level controller)");
  }
  LowLevelOutput output;
  const Eigen::Vector3d eta_hat_B = estimator_.BodyTorque_B();
  if (observer_) {
    observer_->Update(omega_B, eta_hat_B, previous_dt_s_);
    output.torque_disturbance_B = observer_->disturbance_B();
  }
  const Eigen::Vector3d& d_hat_B = output.torque_disturbance_B;
  output.torque_des_B =
      (params_.body_rate_law == LowLevelControllerParameters::BodyRateLaw::kLqr
           ? lqr_.ComputeTorque(command, omega_B, eta_hat_B + d_hat_B)
           : proportional_.ComputeTorque(command.omega_des_B, omega_B)) -
      d_hat_B;
  output.mix = mixer_.Mix(output.torque_des_B, command.collective_thrust_mps2);
  output.motor_commands = MotorCommandsFromRotorThrusts(vehicle_, output.mix.command.thrust_N);
  estimator_.Propagate(output.mix.command, dt_s);
  previous_dt_s_ = dt_s;
  return output;
}

}  // namespace aperture::control
