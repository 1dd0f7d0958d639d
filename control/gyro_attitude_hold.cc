#include "control/gyro_attitude_hold.h"

#include "control/require.h"
#include "control/so3.h"

namespace aperture::control {

GyroAttitudeHold::GyroAttitudeHold(const AttitudeControllerGains& gains) : controller_(gains) {}

void GyroAttitudeHold::AddImu(double t_s, const Eigen::Vector3d& omega_B) {
  RequireFinite(t_s, "GyroAttitudeHold::AddImu t_s");
  RequireFinite(omega_B, "GyroAttitudeHold::AddImu omega_B");
  if (last_t_s_) {
    const double dt_s = t_s - *last_t_s_;
    Require(dt_s >= 0.0, "GyroAttitudeHold::AddImu t_s", t_s, "must not go backwards");
    q_B0B_ = (q_B0B_ * ExpQuaternion(0.5 * (last_omega_B_ + omega_B) * dt_s)).normalized();
  }
  last_t_s_ = t_s;
  last_omega_B_ = omega_B;
}

ThrustRatesCommand GyroAttitudeHold::Command(double collective_thrust_mps2) const {
  ThrustRatesCommand command;
  command.collective_thrust_mps2 = collective_thrust_mps2;
  command.omega_des_B = controller_.Compute(q_B0B_, Eigen::Vector3d::UnitZ(), 0.0).omega_fb_B;
  return command;
}

}  // namespace aperture::control
