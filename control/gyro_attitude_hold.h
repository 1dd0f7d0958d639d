#pragma once
// Holding the attitude a hovering run started in, before any state estimate exists (a mission's
// IMU calibration or gravity averaging at rest): the gyro integrated from the first sample gives
// q_B0B (B0: the body at the first sample, level for a run that starts hovering), and the
// attitude controller's feedback towards z_B0 at hover thrust holds it. Zero-rate commands would
// hold nothing: a weak rotor's torque transient (before the flight controller's torque observer
// takes it) tilts the vehicle by several degrees, which stays, and a calibration "at rest" takes
// the tilt for level and the transient's rates for gyro bias. Gyro bias is not removed (unknown
// before the calibration): ~1e-3 rad/s drifts a fraction of a degree over a second.
//
//   GyroAttitudeHold hold(params.controller.attitude);
//   hold.AddImu(sample.t_s, sample.omega_B);          // every IMU sample until the estimate starts
//   command.thrust_rates = hold.Command(gravity_mps2);
#include <Eigen/Geometry>
#include <optional>

#include "control/attitude_controller.h"
#include "control/commands.h"

namespace aperture::control {

class GyroAttitudeHold {
 public:
  explicit GyroAttitudeHold(const AttitudeControllerGains& gains);

  // Integrates the rate over the step from the previous sample (trapezoidal); the first sample
  // only starts. Throws std::invalid_argument for non-finite input or a time going backwards.
  void AddImu(double t_s, const Eigen::Vector3d& omega_B);
  // Attitude of B in B0 [unit quaternion].
  const Eigen::Quaterniond& q_B0B() const { return q_B0B_; }
  // The collective thrust with the body rates that turn z_B back to z_B0, heading 0 in B0.
  ThrustRatesCommand Command(double collective_thrust_mps2) const;

 private:
  AttitudeController controller_;
  Eigen::Quaterniond q_B0B_ = Eigen::Quaterniond::Identity();
  std::optional<double> last_t_s_;
  Eigen::Vector3d last_omega_B_ = Eigen::Vector3d::Zero();
};

}  // namespace aperture::control
