#include "control/mixer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace aperture::control {
namespace {

// Yaw direction of (G.1): rotors 1 and 3 turn positive yaw torque, 2 and 4 negative.
const Eigen::Vector4d kYawSign(1.0, -1.0, 1.0, -1.0);

// f0: the minimum-norm thrusts achieving eta_x, eta_y and m c with zero yaw component
// (f0 . kYawSign = 0); the roll, pitch, sum and yaw rows of (G.1), (G.2) are orthogonal.
Eigen::Vector4d ThrustsWithoutYaw(double roll_row, double pitch_row, double sum) {
  // roll_row = f1 - f2 - f3 + f4, pitch_row = -f1 - f2 + f3 + f4, sum = f1 + f2 + f3 + f4.
  return 0.25 * Eigen::Vector4d(roll_row - pitch_row + sum, -roll_row - pitch_row + sum,
                                -roll_row + pitch_row + sum, roll_row + pitch_row + sum);
}

// f = f0 + t s with sum s_i kappa_i f_i = eta_z (G.1, third row).
Eigen::Vector4d SolveYaw(const Eigen::Vector4d& f0, double yaw_torque_Nm,
                         const Eigen::Vector4d& kappa) {
  const double t = (yaw_torque_Nm - kYawSign.cwiseProduct(kappa).dot(f0)) / kappa.sum();
  return f0 + t * kYawSign;
}

double MaxViolation(const Eigen::Vector4d& f, const Eigen::Vector4d& lo, const Eigen::Vector4d& hi,
                    int* rotor) {
  const Eigen::Vector4d violation = (f - hi).cwiseMax(lo - f);
  Eigen::Index index = 0;
  const double max_violation = violation.maxCoeff(&index);
  if (rotor != nullptr) *rotor = static_cast<int>(index);
  return max_violation;
}

}  // namespace

std::ostream& operator<<(std::ostream& os, const MixerResult& result) {
  return os << "Mixer: thrust_N [" << result.command.thrust_N.transpose() << "], iterations "
            << result.iterations << (result.converged ? "" : " (not converged)")
            << ", saturated yaw " << result.yaw_torque_saturated << " thrust "
            << result.collective_thrust_saturated << " clipped " << result.clipped
            << ", applied torque_B [" << result.applied_torque_B.transpose() << "] c "
            << result.applied_collective_thrust_mps2;
}

double RotorTorqueCoefficient(const VehicleParameters& vehicle, int rotor_index, double thrust_N) {
  const double gamma = vehicle.rotor_fitness[rotor_index];
  return vehicle.rotor.TorqueCoefficient(thrust_N / gamma);
}

Eigen::Vector3d BodyTorqueFromRotorThrusts(const VehicleParameters& vehicle,
                                           const Eigen::Vector4d& f) {
  const double d = 0.5 * std::sqrt(2.0) * vehicle.arm_length_m;
  double yaw = 0.0;
  for (int i = 0; i < 4; ++i) {
    yaw += VehicleParameters::RotorYawSign(i) * RotorTorqueCoefficient(vehicle, i, f[i]) * f[i];
  }
  // Faessler thesis (G.1)
  return {d * (f[0] - f[1] - f[2] + f[3]), d * (-f[0] - f[1] + f[2] + f[3]), yaw};
}

Eigen::Vector4d MotorCommandsFromRotorThrusts(const VehicleParameters& vehicle,
                                              const Eigen::Vector4d& thrust_N) {
  Eigen::Vector4d u;
  for (int i = 0; i < 4; ++i) {
    u[i] = vehicle.rotor.CommandFromThrust(thrust_N[i] / vehicle.rotor_fitness[i]);
  }
  return u;
}

double CollectiveThrustFromRotorThrusts(const VehicleParameters& vehicle,
                                        const Eigen::Vector4d& f) {
  return f.sum() / vehicle.mass_kg;  // (G.2)
}

Mixer::Mixer(const VehicleParameters& vehicle, const MixerParameters& params)
    : vehicle_(vehicle), params_(params) {
  vehicle_.Validate();
  if (params_.max_iterations < 1) {
    throw std::invalid_argument("MixerParameters.max_iterations must be >= 1, got " +
                                std::to_string(params_.max_iterations));
  }
  if (!(params_.yaw_torque_tolerance_Nm >= 0.0)) {
    throw std::invalid_argument("MixerParameters.yaw_torque_tolerance_Nm must be >= 0");
  }
  if (!(params_.assured_yaw_torque_Nm >= 0.0) || !std::isfinite(params_.assured_yaw_torque_Nm)) {
    throw std::invalid_argument("MixerParameters.assured_yaw_torque_Nm must be finite and >= 0");
  }
  if (!std::isfinite(params_.one_shot_torque_coefficient_m)) {
    throw std::invalid_argument("MixerParameters.one_shot_torque_coefficient_m must be finite");
  }
  half_sqrt2_arm_m_ = 0.5 * std::sqrt(2.0) * vehicle_.arm_length_m;
  one_shot_kappa_m_ =
      params_.one_shot_torque_coefficient_m > 0.0
          ? params_.one_shot_torque_coefficient_m
          : vehicle_.rotor.TorqueCoefficient(0.25 * vehicle_.mass_kg * vehicle_.gravity_mps2);
  min_thrust_N_ = vehicle_.rotor_fitness * vehicle_.rotor.MinThrust();
  max_thrust_N_ = vehicle_.rotor_fitness * vehicle_.rotor.MaxThrust();
}

Eigen::Vector4d Mixer::TorqueCoefficients(const Eigen::Vector4d& f) const {
  return {RotorTorqueCoefficient(vehicle_, 0, f[0]), RotorTorqueCoefficient(vehicle_, 1, f[1]),
          RotorTorqueCoefficient(vehicle_, 2, f[2]), RotorTorqueCoefficient(vehicle_, 3, f[3])};
}

Eigen::Vector4d Mixer::SolveIterative(const Eigen::Vector4d& f0, double yaw_torque_Nm,
                                      Eigen::Vector4d& kappa, MixerResult& result) const {
  Eigen::Vector4d f = f0;
  result.converged = false;
  for (int k = 0; k < params_.max_iterations; ++k) {
    f = SolveYaw(f0, yaw_torque_Nm, kappa);  // step ii)
    ++result.iterations;
    kappa = TorqueCoefficients(f);  // step i) of the next iteration, (G.5)
    const double yaw_error = kYawSign.cwiseProduct(kappa).dot(f) - yaw_torque_Nm;
    if (std::abs(yaw_error) <= params_.yaw_torque_tolerance_Nm) {
      result.converged = true;
      break;
    }
  }
  return f;
}

void Mixer::SaturatePrioritized(const Eigen::Vector4d& f0, double yaw_torque_des_Nm,
                                Eigen::Vector4d& f, MixerResult& result) const {
  const Eigen::Vector4d& lo = min_thrust_N_;
  const Eigen::Vector4d& hi = max_thrust_N_;
  int j = 0;
  // Yaw-torque saturation (G.5.1): pin the worst rotor at its limit by moving along the yaw
  // direction, which leaves eta_x, eta_y and c untouched.
  const double assured = params_.assured_yaw_torque_Nm;
  if (MaxViolation(f, lo, hi, &j) > 0.0 && std::abs(yaw_torque_des_Nm) > assured) {
    const double limit = f[j] > hi[j] ? hi[j] : lo[j];
    const Eigen::Vector4d f_pinned = f0 + (limit - f0[j]) * kYawSign[j] * kYawSign;
    Eigen::Vector4d kappa = TorqueCoefficients(f_pinned);
    const double yaw_pinned = kYawSign.cwiseProduct(kappa).dot(f_pinned);
    // Algorithm 4 leaves eta_z free here; we keep it between the assured value (same sign as the
    // request) and the request, so saturation only ever gives up yaw torque. When roll, pitch or
    // thrust put rotor j over its limit, pinning it may call for more yaw torque than desired:
    // then yaw cannot help and the collective-thrust step below takes over.
    const double sign = yaw_torque_des_Nm > 0.0 ? 1.0 : -1.0;
    const double yaw_lo = std::min(sign * assured, yaw_torque_des_Nm);
    const double yaw_hi = std::max(sign * assured, yaw_torque_des_Nm);
    const double yaw_applied = std::clamp(yaw_pinned, yaw_lo, yaw_hi);
    if (yaw_applied != yaw_torque_des_Nm) {
      result.yaw_torque_saturated = true;
      f = yaw_applied == yaw_pinned ? f_pinned : SolveIterative(f0, yaw_applied, kappa, result);
    }
  }
  // Collective-thrust saturation (G.5.2): shift all thrusts equally (eta_x, eta_y unchanged),
  // possible only when no two rotors violate opposite limits.
  if (MaxViolation(f, lo, hi, &j) > 0.0) {
    const bool above = (f.array() > hi.array()).any();
    const bool below = (f.array() < lo.array()).any();
    if (!(above && below)) {
      f.array() += (f[j] > hi[j] ? hi[j] : lo[j]) - f[j];
      result.collective_thrust_saturated = true;
    }
  }
}

MixerResult Mixer::Mix(const Eigen::Vector3d& torque_des_B,
                       double collective_thrust_des_mps2) const {
  if (!torque_des_B.allFinite() || !std::isfinite(collective_thrust_des_mps2)) {
    throw std::invalid_argument(
        "Mixer::Mix: torque_des_B and collective_thrust_des_mps2 must be "
        "finite (check the body-rate controller output)");
  }
  MixerResult result;
  const double sum_N = vehicle_.mass_kg * collective_thrust_des_mps2;  // (G.2)
  const Eigen::Vector4d f0 = ThrustsWithoutYaw(torque_des_B.x() / half_sqrt2_arm_m_,
                                               torque_des_B.y() / half_sqrt2_arm_m_, sum_N);
  Eigen::Vector4d f;
  if (params_.mixing == MixerParameters::Mixing::kIterative) {
    // (G.13): kappa of the first iteration from equal thrusts m c / 4.
    Eigen::Vector4d kappa = TorqueCoefficients(Eigen::Vector4d::Constant(0.25 * sum_N));
    f = SolveIterative(f0, torque_des_B.z(), kappa, result);
  } else {
    f = SolveYaw(f0, torque_des_B.z(), Eigen::Vector4d::Constant(one_shot_kappa_m_));
    result.iterations = 1;
  }
  if (params_.saturation == MixerParameters::Saturation::kPrioritized) {
    SaturatePrioritized(f0, torque_des_B.z(), f, result);
  }
  // Thrust clipping (G.5.3), the last resort and the whole of the baseline.
  const Eigen::Vector4d clipped = f.cwiseMax(min_thrust_N_).cwiseMin(max_thrust_N_);
  result.clipped = (clipped.array() != f.array()).any();
  result.command.thrust_N = clipped;
  result.applied_torque_B = BodyTorqueFromRotorThrusts(vehicle_, clipped);
  result.applied_collective_thrust_mps2 = CollectiveThrustFromRotorThrusts(vehicle_, clipped);
  return result;
}

}  // namespace aperture::control
