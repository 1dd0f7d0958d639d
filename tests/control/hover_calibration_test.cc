#include "control/hover_calibration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include <Eigen/Geometry>
#include <Eigen/LU>

namespace aperture::control {
namespace {

constexpr int kSamples = 2500;  // 5 s at 500 Hz, the thesis' calibration period (A.5.4)

// Nominal (load-cell) thrusts f_check_i with which rotors of true scale lambda_i hover: the
// true thrusts lambda_i f_check_i give zero torque and c = g, with drag torque
// s_i kappa(f_check_i) lambda_i f_check_i (G.5 at the command's operating point). Solved by
// fixed-point iteration on kappa (it changes by ~10 % over the whole thrust range).
Eigen::Vector4d HoverNominalThrusts(const VehicleParameters& v, const Eigen::Vector4d& lambda) {
  Eigen::Vector4d f_check = Eigen::Vector4d::Constant(v.mass_kg * v.gravity_mps2 / 4.0);
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::Matrix4d A;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d r = v.RotorPosition_B(i);
      A.col(i) << r.y(), -r.x(), VehicleParameters::RotorYawSign(i) *
                                     v.rotor.TorqueCoefficient(f_check(i)),
          1.0 / v.mass_kg;
      A.col(i) *= lambda(i);
    }
    f_check = A.fullPivLu().solve(Eigen::Vector4d(0, 0, 0, v.gravity_mps2));
  }
  return f_check;
}

TEST(HoverCalibration, RecoversInjectedImuBiases) {
  // Hovering with a small tilt: the specific force is g along z_B whatever the attitude (A.21).
  const VehicleParameters vehicle;
  HoverCalibration calibration(vehicle);
  EXPECT_FALSE(calibration.ComputeSensorBiases().has_value());
  const Eigen::Vector3d b_acc(0.15, -0.2, 0.3), b_gyro(0.01, -0.02, 0.005);
  const double sigma_acc = 0.3, sigma_gyro = 0.01;  // noise incl. rotor vibration in hover
  std::mt19937 rng(4);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < kSamples; ++k) {
    const Eigen::Vector3d noise_a(n(rng), n(rng), n(rng)), noise_w(n(rng), n(rng), n(rng));
    calibration.AddImuSample(vehicle.gravity_mps2 * Eigen::Vector3d::UnitZ() + b_acc +
                                 sigma_acc * noise_a,
                             b_gyro + sigma_gyro * noise_w);  // (A.17), (A.20)
  }
  const SensorBiases biases = *calibration.ComputeSensorBiases();
  EXPECT_EQ(biases.num_samples, kSamples);
  // Mean of N samples: standard error sigma / sqrt(N); 5 standard errors.
  const double tol_acc = 5.0 * sigma_acc / std::sqrt(kSamples);
  const double tol_gyro = 5.0 * sigma_gyro / std::sqrt(kSamples);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(biases.accel_bias_B(i), b_acc(i), tol_acc) << i;
    EXPECT_NEAR(biases.gyro_bias_B(i), b_gyro(i), tol_gyro) << i;
  }
}

TEST(HoverCalibration, RecoversRotorThrustScales) {
  const VehicleParameters vehicle;
  const Eigen::Vector4d lambda_true(0.9, 1.05, 0.8, 1.1);  // worn rotors / thin air (A.25)
  const Eigen::Vector4d f_check = HoverNominalThrusts(vehicle, lambda_true);
  HoverCalibration calibration(vehicle);
  EXPECT_FALSE(calibration.ComputeThrustCalibration().has_value());
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  const double sigma_f = 0.02;  // N: commands jitter as the hover controller rejects disturbances
  for (int k = 0; k < kSamples; ++k) {
    calibration.AddNominalThrusts(f_check + sigma_f * Eigen::Vector4d(n(rng), n(rng), n(rng), n(rng)));
  }
  const ThrustCalibration result = *calibration.ComputeThrustCalibration();
  RecordProperty("lambda_error_max", std::to_string((result.lambda - lambda_true).cwiseAbs().maxCoeff()));
  // Noise-free means would give lambda exactly (A.27 is square and regular). With the mean's
  // standard error 0.02 / 50 = 4e-4 N on ~1.1 N (4e-4 relative) and the yaw row's amplification
  // (d / kappa ~ 6), lambda is good to ~3e-3; 1e-2 is the bound.
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(result.lambda(i), lambda_true(i), 1e-2) << i;
  EXPECT_EQ(result.num_samples, kSamples);

  // (A.29): commanding the true hover thrusts through lambda reproduces the nominal thrusts.
  const Eigen::Vector4d f_true = lambda_true.cwiseProduct(f_check);
  const Eigen::Vector4d nominal = HoverCalibration::ToNominalThrust(f_true, result.lambda);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(nominal(i), f_check(i), 1.2e-2 * f_check(i)) << i;
}

TEST(HoverCalibration, NominalVehicleGivesUnitScales) {
  const VehicleParameters vehicle;
  HoverCalibration calibration(vehicle);
  calibration.AddNominalThrusts(HoverNominalThrusts(vehicle, Eigen::Vector4d::Ones()));
  const ThrustCalibration result = *calibration.ComputeThrustCalibration();
  EXPECT_TRUE(result.lambda.isApprox(Eigen::Vector4d::Ones(), 1e-12)) << result.lambda.transpose();
}

TEST(HoverCalibration, RejectsNonHoverThrustData) {
  const VehicleParameters vehicle;
  HoverCalibration calibration(vehicle);
  calibration.AddNominalThrusts(Eigen::Vector4d(1.1, 1.1, 0.0, 1.1));  // a rotor at zero
  EXPECT_FALSE(calibration.ComputeThrustCalibration().has_value());
  // Any positive thrusts have a positive solution (diagonal pairs balance roll and pitch, the
  // pairs' scale ratio balances yaw): very uneven data are accepted and give uneven scales.
  calibration.Reset();
  calibration.AddNominalThrusts(Eigen::Vector4d(2.0, 0.5, 2.0, 0.5));
  const ThrustCalibration uneven = *calibration.ComputeThrustCalibration();
  EXPECT_NEAR(uneven.lambda(0) * 2.0, uneven.lambda(2) * 2.0, 1e-12);
  EXPECT_GT(uneven.lambda(1) / uneven.lambda(0), 3.0);
  EXPECT_THROW(HoverCalibration::ToNominalThrust(Eigen::Vector4d::Ones(),
                                                 Eigen::Vector4d(1, 1, 0, 1)),
               std::invalid_argument);
  EXPECT_THROW(calibration.AddImuSample(Eigen::Vector3d(NAN, 0, 0), Eigen::Vector3d::Zero()),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
