#include "control/vehicle_parameters.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/require.h"

namespace aperture::control {
namespace {

double EvaluateQuadratic(const Eigen::Vector3d& k, double u) {
  return (k[2] * u + k[1]) * u + k[0];
}

}  // namespace

double RotorParameters::ThrustFromCommand(double u) const {
  return EvaluateQuadratic(thrust_coeffs_N, u);
}

double RotorParameters::DragTorqueFromCommand(double u) const {
  return EvaluateQuadratic(torque_coeffs_Nm, u);
}

double RotorParameters::CommandFromThrust(double f_N) const {
  const double f = std::clamp(f_N, MinThrust(), MaxThrust());
  const double k0 = thrust_coeffs_N[0], k1 = thrust_coeffs_N[1], k2 = thrust_coeffs_N[2];
  // Rising root of k2 u^2 + k1 u + (k0 - f) = 0, the argument of tau in (G.5). For k1 >= 0 it is
  // written as 2 (f - k0) / (k1 + sqrt(D)): the textbook (-k1 + sqrt(D)) / (2 k2) loses all digits
  // to cancellation when 4 k2 (f - k0) << k1^2 and divides by zero for a linear map (k2 = 0).
  // For k1 < 0 the textbook form has no cancellation (and Validate() then implies k2 > 0).
  const double sqrt_discriminant = std::sqrt(std::max(0.0, k1 * k1 - 4.0 * k2 * (k0 - f)));
  double u = 0.0;
  if (k1 >= 0.0) {
    const double denominator = k1 + sqrt_discriminant;
    u = denominator > 0.0 ? 2.0 * (f - k0) / denominator : 0.0;  // 0: k1 = 0 and f = k0
  } else {
    u = (-k1 + sqrt_discriminant) / (2.0 * k2);
  }
  return std::clamp(u, command_min, command_max);
}

double RotorParameters::TorqueCoefficient(double f_N) const {
  // Outside the thrust range kappa is held at its value at the nearest limit: the mixer's
  // saturation (Algorithm 4) evaluates yaw torques of intermediate, infeasible thrusts, and
  // tau(u_max) / f would make kappa vanish as 1 / f there (and flip the sign of their yaw torque).
  const double f = std::clamp(f_N, std::max(MinThrust(), 1e-6), MaxThrust());
  return DragTorqueFromCommand(CommandFromThrust(f)) / f;
}

Eigen::Vector3d VehicleParameters::RotorPosition_B(int i) const {
  static constexpr double kSigns[4][2] = {{1, 1}, {1, -1}, {-1, -1}, {-1, 1}};
  const double d = arm_length_m / std::sqrt(2.0);
  return {kSigns[i][0] * d, kSigns[i][1] * d, 0.0};
}

void VehicleParameters::Validate() const {
  RequirePositive(mass_kg, "VehicleParameters.mass_kg");
  for (int i = 0; i < 3; ++i)
    RequirePositive(inertia_diag_kgm2[i], "VehicleParameters.inertia_diag_kgm2");
  RequirePositive(arm_length_m, "VehicleParameters.arm_length_m");
  RequirePositive(gravity_mps2, "VehicleParameters.gravity_mps2");
  RequirePositive(rotor.time_constant_up_s, "VehicleParameters.rotor.time_constant_up_s");
  RequirePositive(rotor.time_constant_down_s, "VehicleParameters.rotor.time_constant_down_s");
  for (int i = 0; i < 4; ++i) RequirePositive(rotor_fitness[i], "VehicleParameters.rotor_fitness");
  if (!(rotor_drag_D_per_s.allFinite() && rotor_drag_A.allFinite() && rotor_drag_B.allFinite() &&
        std::isfinite(thrust_velocity_coeff_kh))) {
    throw std::invalid_argument(
        "vehicle parameters: rotor drag terms (D, A, B, k_h) must be finite");
  }
  if (!(rotor.thrust_coeffs_N.allFinite() && rotor.torque_coeffs_Nm.allFinite())) {
    throw std::invalid_argument(
        "vehicle parameters: rotor.thrust_coeffs_N / torque_coeffs_Nm must be finite");
  }
  if (!(std::isfinite(rotor.command_min) && std::isfinite(rotor.command_max) &&
        rotor.command_max > rotor.command_min)) {
    throw std::invalid_argument("vehicle parameter 'rotor.command_max' must exceed 'command_min'");
  }
  // The thrust map must rise over the command range for (G.5) to be well defined.
  const Eigen::Vector3d& k = rotor.thrust_coeffs_N;
  const double slope_min = 2.0 * k[2] * rotor.command_min + k[1];
  const double slope_max = 2.0 * k[2] * rotor.command_max + k[1];
  if (!(slope_min >= 0.0 && slope_max > 0.0) || rotor.MinThrust() < 0.0) {
    throw std::invalid_argument(
        "vehicle parameter 'rotor.thrust_coeffs_N' must give a non-negative thrust that increases "
        "over [command_min, command_max]");
  }
  // kappa(f) of (G.5) must stay positive: the mixer divides the yaw torque by sum(kappa_i).
  const Eigen::Vector3d& kt = rotor.torque_coeffs_Nm;
  double torque_min = std::min(rotor.DragTorqueFromCommand(rotor.command_min),
                               rotor.DragTorqueFromCommand(rotor.command_max));
  if (kt[2] > 0.0) {
    const double u_vertex = -kt[1] / (2.0 * kt[2]);
    if (u_vertex > rotor.command_min && u_vertex < rotor.command_max) {
      torque_min = std::min(torque_min, rotor.DragTorqueFromCommand(u_vertex));
    }
  }
  if (!(torque_min > 0.0)) {
    throw std::invalid_argument(
        "vehicle parameter 'rotor.torque_coeffs_Nm' must give a positive drag torque over "
        "[command_min, command_max] (min " +
        std::to_string(torque_min) + " N m)");
  }
}

}  // namespace aperture::control
