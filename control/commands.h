#pragma once
// Commands that cross the autopilot / flight-controller boundary (DESIGN.md data flow).
#include <Eigen/Core>

namespace aperture::control {

// High-level output: mass-normalized collective thrust and desired body rates, as computed by the
// position/attitude controller with flatness feed-forward (Faessler thesis F.31-F.38). The
// low-level loop (LQR or P body-rate control, then the mixer) runs in the flight controller.
struct ThrustRatesCommand {
  double collective_thrust_mps2 = 0.0;                           // c_cmd, mass-normalized [m/s^2]
  Eigen::Vector3d omega_des_B = Eigen::Vector3d::Zero();         // [rad/s]
  Eigen::Vector3d omega_dot_des_B = Eigen::Vector3d::Zero();     // feed-forward [rad/s^2]
};

// Single-rotor thrusts in the rotor numbering of thesis (G.1) [N].
struct RotorThrustCommand {
  Eigen::Vector4d thrust_N = Eigen::Vector4d::Zero();
};

}  // namespace aperture::control
