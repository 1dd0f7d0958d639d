#include "control/rotor_thrust_estimator.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "control/mixer.h"

namespace aperture::control {

RotorThrustEstimator::RotorThrustEstimator(const VehicleParameters& vehicle) : vehicle_(vehicle) {
  vehicle_.Validate();
  thrust_N_.setConstant(0.25 * vehicle_.mass_kg * vehicle_.gravity_mps2);
}

void RotorThrustEstimator::Reset(const Eigen::Vector4d& thrust_N) {
  if (!thrust_N.allFinite()) {
    throw std::invalid_argument("RotorThrustEstimator::Reset: thrust_N must be finite");
  }
  thrust_N_ = thrust_N;
}

void RotorThrustEstimator::Propagate(const RotorThrustCommand& command, double dt_s) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    throw std::invalid_argument(
        "RotorThrustEstimator::Propagate: dt_s must be finite and > 0, got " +
        std::to_string(dt_s));
  }
  if (!command.thrust_N.allFinite()) {
    throw std::invalid_argument("RotorThrustEstimator::Propagate: command.thrust_N must be finite");
  }
  const double decay_up = std::exp(-dt_s / vehicle_.rotor.time_constant_up_s);
  const double decay_down = std::exp(-dt_s / vehicle_.rotor.time_constant_down_s);
  for (int i = 0; i < 4; ++i) {
    const double f_des = command.thrust_N[i];
    const double decay = f_des >= thrust_N_[i] ? decay_up : decay_down;  // (G.7)
    thrust_N_[i] = f_des + (thrust_N_[i] - f_des) * decay;
  }
}

Eigen::Vector3d RotorThrustEstimator::BodyTorque_B() const {
  return BodyTorqueFromRotorThrusts(vehicle_, thrust_N_);
}

}  // namespace aperture::control
