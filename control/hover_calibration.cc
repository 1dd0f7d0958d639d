#include "control/hover_calibration.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

namespace aperture::control {

HoverCalibration::HoverCalibration(const VehicleParameters& vehicle) : vehicle_(vehicle) {
  vehicle_.Validate();
}

void HoverCalibration::Reset() { *this = HoverCalibration(vehicle_); }

void HoverCalibration::AddImuSample(const Eigen::Vector3d& specific_force_B,
                                    const Eigen::Vector3d& omega_B) {
  if (!specific_force_B.allFinite() || !omega_B.allFinite()) {
    throw std::invalid_argument("HoverCalibration::AddImuSample: non-finite IMU sample");
  }
  sum_specific_force_B_ += specific_force_B;
  sum_omega_B_ += omega_B;
  ++num_imu_samples_;
}

void HoverCalibration::AddNominalThrusts(const Eigen::Vector4d& nominal_thrust_N) {
  if (!nominal_thrust_N.allFinite()) {
    throw std::invalid_argument("HoverCalibration::AddNominalThrusts: non-finite thrust");
  }
  sum_nominal_thrust_N_ += nominal_thrust_N;
  ++num_thrust_samples_;
}

std::optional<SensorBiases> HoverCalibration::ComputeSensorBiases() const {
  if (num_imu_samples_ == 0) return std::nullopt;
  const double n = static_cast<double>(num_imu_samples_);
  SensorBiases biases;
  biases.gyro_bias_B = sum_omega_B_ / n;  // (A.19)
  biases.accel_bias_B =
      sum_specific_force_B_ / n - vehicle_.gravity_mps2 * Eigen::Vector3d::UnitZ();  // (A.22)
  biases.num_samples = num_imu_samples_;
  return biases;
}

std::optional<ThrustCalibration> HoverCalibration::ComputeThrustCalibration() const {
  if (num_thrust_samples_ == 0) return std::nullopt;
  ThrustCalibration out;
  out.num_samples = num_thrust_samples_;
  out.mean_nominal_thrust_N = sum_nominal_thrust_N_ / static_cast<double>(num_thrust_samples_);
  if (!(out.mean_nominal_thrust_N.minCoeff() > 0.0)) return std::nullopt;
  // (A.27): columns are rotor i's contribution per unit lambda_i.
  Eigen::Matrix4d A;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d r = vehicle_.RotorPosition_B(i);
    const double f = out.mean_nominal_thrust_N(i);
    const double kappa = vehicle_.rotor.TorqueCoefficient(f);  // (G.5) at the operating point
    A.col(i) << r.y() * f, -r.x() * f, VehicleParameters::RotorYawSign(i) * kappa * f,
        f / vehicle_.mass_kg;
  }
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(A);
  if (!lu.isInvertible()) return std::nullopt;
  out.lambda = lu.solve(Eigen::Vector4d(0.0, 0.0, 0.0, vehicle_.gravity_mps2));
  if (!out.lambda.allFinite() || !(out.lambda.minCoeff() > 0.0)) return std::nullopt;
  return out;
}

Eigen::Vector4d HoverCalibration::ToNominalThrust(const Eigen::Vector4d& desired_thrust_N,
                                                  const Eigen::Vector4d& lambda) {
  if (!lambda.allFinite() || !(lambda.minCoeff() > 0.0)) {
    throw std::invalid_argument(
        "HoverCalibration::ToNominalThrust: every lambda must be finite and > 0; run "
        "ComputeThrustCalibration on hover data");
  }
  return desired_thrust_N.cwiseQuotient(lambda);  // (A.29)
}

}  // namespace aperture::control
