#pragma once
// The flight controller of the simulated vehicle (DESIGN.md data flow, Faessler thesis App. G):
// at its own rate (1 kHz by default) it turns the autopilot's latest command into rotor thrust
// commands for QuadrotorDynamics, as the flight-controller board does on hardware:
//   kThrustRates  -> control::LowLevelController (LQR (G.12) or P (B.21) body-rate law on the
//                    IMU gyro, iterative mixer (G.4), prioritized saturation (Algorithm 4),
//                    torque-disturbance observer)
//   kRotorThrusts -> passed through, clamped to [MinThrust, MaxThrust] of the rotor model
//   kNone         -> every rotor at MinThrust (motors idling)
// The gyro it uses is the latest IMU sample delivered to it (noise, bias and latency included).
#include <Eigen/Core>

#include "control/commands.h"
#include "control/low_level_controller.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"

namespace aperture::sim {

struct SimulatedFlightControllerParams {
  double rate_hz = 1000.0;  // low-level loop rate (thesis G: 1 kHz on the flight controller)
  // LQR + iterative mixer + Algorithm 4, and (beyond the thesis) the torque-disturbance observer
  // that a flight controller flying missions needs against a weak rotor (0.1 s; the control
  // benches and flows set their `control` block here, where it is off unless configured).
  control::LowLevelControllerParameters low_level = WithTorqueObserver(0.1);

  static control::LowLevelControllerParameters WithTorqueObserver(double time_constant_s) {
    control::LowLevelControllerParameters params;
    params.torque_observer_time_constant_s = time_constant_s;
    return params;
  }
  // Throws std::invalid_argument naming the field when rate_hz is not positive and finite.
  void Validate() const;
};

class SimulatedFlightController {
 public:
  // `vehicle` is the controller's model of the vehicle (usually the simulated one); throws
  // std::invalid_argument for invalid parameters.
  SimulatedFlightController(const control::VehicleParameters& vehicle,
                            const SimulatedFlightControllerParams& params = {});
  void SetCommand(const perception::AutopilotCommand& command) { command_ = command; }
  void SetGyro(const Eigen::Vector3d& omega_B) { omega_B_ = omega_B; }
  // Starts the rotor thrust estimate at `thrust_N` (e.g. hover thrusts for an airborne start).
  void ResetThrustEstimate(const Eigen::Vector4d& thrust_N) {
    low_level_.ResetThrustEstimate(thrust_N);
  }
  // One control period of 1 / rate_hz: the thrusts to hold until the next call.
  control::RotorThrustCommand Step();
  const control::LowLevelOutput& last_low_level_output() const { return last_output_; }
  const SimulatedFlightControllerParams& params() const { return params_; }

 private:
  control::VehicleParameters vehicle_;
  SimulatedFlightControllerParams params_;
  control::LowLevelController low_level_;
  perception::AutopilotCommand command_;
  Eigen::Vector3d omega_B_ = Eigen::Vector3d::Zero();
  control::LowLevelOutput last_output_;
};

}  // namespace aperture::sim
