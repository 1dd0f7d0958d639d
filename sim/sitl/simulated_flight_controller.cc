#include "sim/sitl/simulated_flight_controller.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace aperture::sim {

void SimulatedFlightControllerParams::Validate() const {
  if (!std::isfinite(rate_hz) || rate_hz <= 0.0) {
    throw std::invalid_argument("SimulatedFlightControllerParams.rate_hz = " +
                                std::to_string(rate_hz) + " must be positive (e.g. 1000)");
  }
  low_level.Validate();
}

SimulatedFlightController::SimulatedFlightController(const control::VehicleParameters& vehicle,
                                                     const SimulatedFlightControllerParams& params)
    : vehicle_(vehicle), params_(params), low_level_(vehicle, params.low_level) {
  params_.Validate();
}

control::RotorThrustCommand SimulatedFlightController::Step() {
  const double dt_s = 1.0 / params_.rate_hz;
  const double f_min = vehicle_.rotor.MinThrust();
  const double f_max = vehicle_.rotor.MaxThrust();
  control::RotorThrustCommand out;
  switch (command_.kind) {
    case perception::AutopilotCommand::Kind::kThrustRates:
      last_output_ = low_level_.Step(command_.thrust_rates, omega_B_, dt_s);
      return last_output_.mix.command;
    case perception::AutopilotCommand::Kind::kRotorThrusts:
      out.thrust_N = command_.rotor_thrusts.thrust_N.cwiseMax(f_min).cwiseMin(f_max);
      break;
    case perception::AutopilotCommand::Kind::kNone:
      out.thrust_N.setConstant(f_min);
      break;
  }
  // Restart the LQR's thrust estimate at the commanded thrusts (their lag ignored), so a later
  // switch to kThrustRates does not start from a stale estimate.
  low_level_.ResetThrustEstimate(out.thrust_N);
  last_output_ = control::LowLevelOutput();
  last_output_.mix.command = out;
  return out;
}

}  // namespace aperture::sim
