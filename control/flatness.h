#pragma once
// Differential flatness of the quadrotor with linear rotor drag, Faessler thesis Appendix F
// (F.1)-(F.30): maps one sample of the flat outputs (position and its derivatives up to snap,
// heading psi and two derivatives) to the full reference state and inputs.
//
//   in : TrajectoryPoint (W frame, SI), VehicleParameters (mass-normalized drag D = diag(dx,dy,dz),
//        thrust-velocity coefficient k_h, inertia J, torque-drag matrices A, B; gravity g)
//   out: R_WB = [x_B y_B z_B] (F.11)-(F.13), collective thrust c (F.14) and command c_cmd (F.15),
//        body rates omega_B (F.17, F.18, F.25), angular accelerations omega_dot_B (F.26)-(F.30),
//        torque input tau_B of (F.4) with tau_g = 0 (rotor gyroscopic torques are not modelled).
//
// Degenerate references never produce NaN; they set `status` and use documented fallbacks:
//  * kNoThrust: alpha = a + g z_W + dx v or beta = a + g z_W + dy v (F.7, F.8) has a norm below
//    kMinThrust_mps2 (free-fall reference), so the thrust direction is undefined. R_WB falls back
//    to the pure heading rotation Rz(psi) (z_B = z_W), omega_B = [0, 0, psi_dot],
//    omega_dot_B = [0, 0, psi_ddot] (the exact rates of Rz(psi(t))); c and c_cmd are evaluated
//    with that z_B by (F.14), (F.15) and are close to zero.
//  * kLowThrust: the thrust direction is defined but a pivot of the body-rate system
//    (F.17)/(F.18) (c - (dz - dx) z_B'v or c + (dy - dz) z_B'v, see flatness.cc) is below
//    kMinThrust_mps2, so roll and pitch rates are unobservable from the jerk: omega_x = omega_y = 0
//    (and their derivatives), omega_z still from (F.25)/(F.28).
//  * kYawSingular: the heading is undefined because alpha is (nearly) parallel to y_C, i.e.
//    |y_C x alpha| / |alpha| < kYawSingularity (F.11 and F.25 divide by it). Fallback: x_B is
//    x_C made orthogonal to alpha (Gram-Schmidt), which is the limit of (F.11) when the
//    singularity is approached with thrust pointing upwards (alpha_z > 0), so the orientation is
//    continuous from that side; rows (F.25)/(F.28) are replaced by omega_z = omega_dot_z = 0, as
//    the attitude controller does for its own singularity (thesis B.18 text).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <iosfwd>

#include "control/trajectory_point.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {

enum class FlatnessStatus { kOk, kYawSingular, kLowThrust, kNoThrust };
const char* ToString(FlatnessStatus status);

struct FlatnessResult {
  FlatnessStatus status = FlatnessStatus::kOk;
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();        // [x_B y_B z_B] in W (F.11-F.13)
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  // same rotation as R_WB
  double collective_thrust_mps2 = 0.0;                       // c (F.14) [m/s^2]
  double collective_thrust_rate_mps3 = 0.0;                  // c dot (F.29) [m/s^3]
  double thrust_command_mps2 = 0.0;                          // c_cmd (F.15) [m/s^2]
  Eigen::Vector3d omega_B = Eigen::Vector3d::Zero();         // body rates [rad/s]
  Eigen::Vector3d omega_dot_B = Eigen::Vector3d::Zero();     // angular accelerations [rad/s^2]
  Eigen::Vector3d tau_B_Nm = Eigen::Vector3d::Zero();        // torque input of (F.4) [N m]

  bool ok() const { return status == FlatnessStatus::kOk; }
};
std::ostream& operator<<(std::ostream& os, const FlatnessResult& result);

// Thrust below which the thrust direction (kNoThrust) or the roll/pitch rates (kLowThrust) are
// treated as undefined [m/s^2]. At 1e-2 m/s^2 a jerk of 1 m/s^3 would need 100 rad/s, far outside
// any vehicle's envelope, while every flyable reference stays far above it.
inline constexpr double kMinThrust_mps2 = 1e-2;
// sin of the angle between alpha and y_C below which the heading is treated as singular. At 1e-3
// the exact yaw rate of (F.25) would already be ~1000 times the heading rate.
inline constexpr double kYawSingularity = 1e-3;

// Full flatness map (F.6)-(F.30) plus the torque of (F.4). Throws std::invalid_argument naming
// the field when the reference contains a non-finite value.
FlatnessResult ComputeFlatnessOutputs(const TrajectoryPoint& reference,
                                      const VehicleParameters& vehicle);

}  // namespace aperture::control
