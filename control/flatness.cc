#include "control/flatness.h"

#include <cmath>
#include <ostream>
#include <stdexcept>
#include <string>

#include "control/so3.h"

namespace aperture::control {
namespace {

void CheckFinite(const TrajectoryPoint& reference) {
  if (!reference.IsFinite()) {
    throw std::invalid_argument(
        "ComputeFlatnessOutputs: reference at t = " + std::to_string(reference.t_s) +
        " s has a non-finite position derivative or heading; fix the trajectory that produced it");
  }
}

// The body-rate systems (F.17, F.18, F.25) and (F.26)-(F.28) share one matrix
//   [ 0    c1  -delta*yv ]
//   [ c2   0    delta*xv ]
//   [ 0  -yczb     n     ]
// with delta = dx - dy, xv = x_B'v, yv = y_B'v, yczb = y_C'z_B, n = |y_C x z_B| (F.25 multiplied
// by n). It is solved by elimination: row 3 gives omega_z from omega_y, rows 1 and 2 then need the
// pivots e1 = c1 - delta*yv*yczb/n and c2.
struct RateSystem {
  double c1 = 0.0, c2 = 0.0, delta_xv = 0.0, delta_yv = 0.0, yczb = 0.0, n = 1.0;
  bool roll_pitch_defined = true;  // both pivots above kMinThrust_mps2

  double PivotOne() const { return c1 - delta_yv * yczb / n; }

  Eigen::Vector3d Solve(double r1, double r2, double r3) const {
    Eigen::Vector3d w;
    if (!roll_pitch_defined) {
      w << 0.0, 0.0, r3 / n;
      return w;
    }
    w.y() = (r1 + delta_yv * r3 / n) / PivotOne();
    w.z() = (r3 + yczb * w.y()) / n;
    w.x() = (r2 - delta_xv * w.z()) / c2;
    return w;
  }
};

}  // namespace

const char* ToString(FlatnessStatus status) {
  switch (status) {
    case FlatnessStatus::kOk:
      return "ok";
    case FlatnessStatus::kYawSingular:
      return "yaw_singular";
    case FlatnessStatus::kLowThrust:
      return "low_thrust";
    case FlatnessStatus::kNoThrust:
      return "no_thrust";
  }
  return "unknown";
}

std::ostream& operator<<(std::ostream& os, const FlatnessResult& result) {
  const Eigen::IOFormat row(Eigen::StreamPrecision, 0, ", ", ", ", "", "", "[", "]");
  return os << "FlatnessResult{status=" << ToString(result.status)
            << ", c=" << result.collective_thrust_mps2 << ", c_cmd=" << result.thrust_command_mps2
            << ", omega_B=" << result.omega_B.transpose().format(row)
            << ", omega_dot_B=" << result.omega_dot_B.transpose().format(row)
            << ", tau_B=" << result.tau_B_Nm.transpose().format(row) << "}";
}

FlatnessResult ComputeFlatnessOutputs(const TrajectoryPoint& reference,
                                      const VehicleParameters& vehicle) {
  CheckFinite(reference);
  const Eigen::Vector3d& v = reference.v_W;
  const Eigen::Vector3d& a = reference.a_W;
  const Eigen::Vector3d& j = reference.j_W;
  const Eigen::Vector3d& s = reference.s_W;
  const Eigen::Vector3d& d = vehicle.rotor_drag_D_per_s;
  const double dx = d.x(), dy = d.y(), dz = d.z();
  const double psi_dot = reference.heading_rate_radps;
  const double psi_ddot = reference.heading_acc_radps2;

  const double cos_psi = std::cos(reference.heading_rad);
  const double sin_psi = std::sin(reference.heading_rad);
  const Eigen::Vector3d x_C(cos_psi, sin_psi, 0.0);   // (F.9)
  const Eigen::Vector3d y_C(-sin_psi, cos_psi, 0.0);  // (F.10)

  const Eigen::Vector3d a_plus_g = a + vehicle.gravity_mps2 * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d alpha = a_plus_g + dx * v;  // (F.7)
  const Eigen::Vector3d beta = a_plus_g + dy * v;   // (F.8)

  bool no_thrust = false;
  bool yaw_singular = false;
  Eigen::Vector3d x_B = x_C, y_B = y_C, z_B = Eigen::Vector3d::UnitZ();
  const double alpha_norm = alpha.norm();
  if (alpha_norm < kMinThrust_mps2 || beta.norm() < kMinThrust_mps2) {
    no_thrust = true;
  } else {
    Eigen::Vector3d x_tilde = y_C.cross(alpha);  // (F.11)
    if (x_tilde.norm() < kYawSingularity * alpha_norm) {
      yaw_singular = true;
      const Eigen::Vector3d alpha_hat = alpha / alpha_norm;
      x_tilde = x_C - x_C.dot(alpha_hat) * alpha_hat;  // |x_tilde| ~ 1 since alpha ~ along y_C
    }
    const Eigen::Vector3d x_B_candidate = x_tilde.normalized();
    const Eigen::Vector3d y_tilde = beta.cross(x_B_candidate);  // (F.12)
    // |beta x x_B| is the thrust component that (F.12) can point y_B with; below the threshold
    // the thrust direction is as undefined as for a free-fall reference.
    if (y_tilde.norm() < kMinThrust_mps2) {
      no_thrust = true;
      yaw_singular = false;
    } else {
      x_B = x_B_candidate;
      y_B = y_tilde.normalized();
      z_B = x_B.cross(y_B);  // (F.13)
    }
  }

  FlatnessResult result;
  result.R_WB.col(0) = x_B;
  result.R_WB.col(1) = y_B;
  result.R_WB.col(2) = z_B;
  result.q_WB = Eigen::Quaterniond(result.R_WB).normalized();

  const double c = z_B.dot(a_plus_g + dz * v);  // (F.14)
  const double v_h = v.dot(x_B + y_B);
  result.collective_thrust_mps2 = c;
  result.thrust_command_mps2 = c - vehicle.thrust_velocity_coeff_kh * v_h * v_h;  // (F.15)

  const double xv = x_B.dot(v), yv = y_B.dot(v), zv = z_B.dot(v);
  RateSystem system;
  system.c1 = c - (dz - dx) * zv;  // (F.17)
  system.c2 = c + (dy - dz) * zv;  // (F.18)
  system.delta_xv = (dx - dy) * xv;
  system.delta_yv = (dx - dy) * yv;
  if (!no_thrust) {
    const double n = y_C.cross(z_B).norm();
    if (n < kYawSingularity) yaw_singular = true;
    // In the yaw singularity row 3 becomes omega_z = 0 (B.18 text): n = 1, y_C'z_B = 0, rhs 0.
    system.n = yaw_singular ? 1.0 : n;
    system.yczb = yaw_singular ? 0.0 : y_C.dot(z_B);
  }
  system.roll_pitch_defined = !no_thrust && std::abs(system.PivotOne()) >= kMinThrust_mps2 &&
                              std::abs(system.c2) >= kMinThrust_mps2;

  // Body rates (F.17), (F.18), (F.25).
  const double r3_rate = yaw_singular ? 0.0 : psi_dot * x_C.dot(x_B);
  const Eigen::Vector3d w =
      system.Solve(x_B.dot(j) + dx * x_B.dot(a), -y_B.dot(j) - dy * y_B.dot(a), r3_rate);
  result.omega_B = w;

  // Angular accelerations (F.26)-(F.30).
  const double c_dot =
      z_B.dot(j) + w.x() * (dy - dz) * yv + w.y() * (dz - dx) * xv + dz * z_B.dot(a);  // (F.29)
  result.collective_thrust_rate_mps3 = c_dot;
  const Eigen::Matrix3d W = Skew(w);
  const Eigen::Matrix3d D = d.asDiagonal();
  const Eigen::Matrix3d& R = result.R_WB;
  const Eigen::Matrix3d W2 = W * W;
  const Eigen::Vector3d xi =
      R * ((W2 * D + D * W2 + 2.0 * W * D * W.transpose()) * (R.transpose() * v) +
           2.0 * (W * D + D * W.transpose()) * (R.transpose() * a) +
           D * (R.transpose() * j));  // (F.30)
  const double r1_acc = x_B.dot(s) - 2.0 * c_dot * w.y() - c * w.x() * w.z() + x_B.dot(xi);
  const double r2_acc = -y_B.dot(s) - 2.0 * c_dot * w.x() + c * w.y() * w.z() - y_B.dot(xi);
  const double r3_acc =
      yaw_singular ? 0.0
                   : psi_ddot * x_C.dot(x_B) + 2.0 * psi_dot * w.z() * x_C.dot(y_B) -
                         2.0 * psi_dot * w.y() * x_C.dot(z_B) - w.x() * w.y() * y_C.dot(y_B) -
                         w.x() * w.z() * y_C.dot(z_B);  // (F.28)
  result.omega_dot_B = system.Solve(r1_acc, r2_acc, r3_acc);

  // Torque input from (F.4) with tau_g = 0.
  const Eigen::Matrix3d J = vehicle.Inertia();
  result.tau_B_Nm = J * result.omega_dot_B + w.cross(J * w) +
                    vehicle.rotor_drag_A * (R.transpose() * v) + vehicle.rotor_drag_B * w;

  if (no_thrust) {
    result.status = FlatnessStatus::kNoThrust;
  } else if (!system.roll_pitch_defined) {
    result.status = FlatnessStatus::kLowThrust;
  } else if (yaw_singular) {
    result.status = FlatnessStatus::kYawSingular;
  }
  return result;
}

}  // namespace aperture::control
