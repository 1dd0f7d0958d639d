// Hover calibration (Faessler thesis A.5.4, (A.17)-(A.29)) on the simulated vehicle: the vehicle
// hovers under the position controller (B.8 / F.31-F.38), the B.21 rate loop and the mixer, whose
// model assumes nominal rotors, while the simulated rotors have thrust scales lambda_i (rotor
// fitness) and the simulated IMU has biases. 5 s of hover data, as in the thesis, must recover
// both; commanding through the calibration (A.29) then hovers with a level body.
#include <gtest/gtest.h>

#include <cmath>

#include "control/hover_calibration.h"
#include "control/mixer.h"
#include "control/position_controller.h"
#include "control/proportional_body_rate_controller.h"
#include "sim/sensors/imu_sensor.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture {
namespace {

constexpr double kHoverCalibrationDt_s = 0.002;

TEST(HoverCalibrationSim, RecoversRotorScalesAndImuBiasesInHover) {
  const control::VehicleParameters nominal;  // what the flight controller believes
  sim::QuadrotorDynamicsParams sim_params;
  const Eigen::Vector4d lambda_true(0.92, 1.04, 0.85, 1.08);
  sim_params.vehicle.rotor_fitness = lambda_true;
  control::QuadState start;
  start.p_WB = Eigen::Vector3d(0, 0, 1);
  sim::QuadrotorDynamics dynamics(sim_params, start);
  sim::ImuSensorParams imu_params;
  imu_params.latency_s = 0.0;
  imu_params.accel_bias_initial_B = Eigen::Vector3d(0.2, -0.15, 0.25);
  imu_params.gyro_bias_initial_B = Eigen::Vector3d(0.01, -0.008, 0.004);
  sim::ImuSensor imu(imu_params);

  const control::PositionController position(nominal);
  const control::ProportionalBodyRateController rates(nominal);
  const control::Mixer mixer(nominal);
  control::HoverCalibration calibration(nominal);
  control::TrajectoryPoint hover;
  hover.p_W = start.p_WB;

  Eigen::Vector3d mean_accel_bias = Eigen::Vector3d::Zero(),
                  mean_gyro_bias = Eigen::Vector3d::Zero();
  int bias_samples = 0;
  for (int k = 1; k <= 4000; ++k) {  // 3 s to settle, then 5 s of calibration data
    const double t = k * kHoverCalibrationDt_s;
    const control::QuadState& truth = dynamics.state();
    const control::ThrustRatesCommand command = position.Compute(truth, hover).command;
    const control::MixerResult mixed = mixer.Mix(
        rates.ComputeTorque(command.omega_des_B, truth.omega_B), command.collective_thrust_mps2);
    dynamics.SetRotorThrustCommand(mixed.command);
    dynamics.Step(kHoverCalibrationDt_s);
    const bool calibrating = t > 3.0;
    for (const perception::ImuSample& s :
         imu.Update(t, dynamics.SpecificForce_B(), dynamics.state().omega_B)) {
      if (!calibrating) continue;
      calibration.AddImuSample(s.specific_force_B, s.omega_B);
      mean_accel_bias += imu.accel_bias_B();
      mean_gyro_bias += imu.gyro_bias_B();
      ++bias_samples;
    }
    // The nominal thrusts of the applied commands (A.28): the mixer's model has gamma = 1, so
    // they are the mixer's thrusts (the simulator turns them into lambda_i times as much).
    if (calibrating) calibration.AddNominalThrusts(mixed.command.thrust_N);
  }
  mean_accel_bias /= bias_samples;
  mean_gyro_bias /= bias_samples;

  const control::ThrustCalibration thrust = *calibration.ComputeThrustCalibration();
  RecordProperty("lambda_error_max",
                 ::testing::PrintToString((thrust.lambda - lambda_true).cwiseAbs().maxCoeff()));
  // After 3 s the hover is steady (P-only loops leave a constant attitude offset, no
  // oscillation), so (A.27) holds up to the residual motion: measured 4e-7; bound 1e-4.
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(thrust.lambda(i), lambda_true(i), 1e-4) << i;

  const control::SensorBiases biases = *calibration.ComputeSensorBiases();
  // Against the mean of the (random-walking) true bias: white noise averages to
  // 0.087 / sqrt(2500) = 2e-3 m/s^2 and 2e-6 rad/s; residual hover motion adds a little.
  EXPECT_LT((biases.accel_bias_B - mean_accel_bias).norm(), 0.01);
  EXPECT_LT((biases.gyro_bias_B - mean_gyro_bias).norm(), 1e-4);

  // (A.29): commanding the nominal thrusts f / lambda makes the true thrusts what the mixer
  // computed for the nominal model: the torque-free hover thrusts are then exact.
  const control::MixerResult hover_mix = mixer.Mix(Eigen::Vector3d::Zero(), nominal.gravity_mps2);
  control::RotorThrustCommand calibrated;
  calibrated.thrust_N =
      control::HoverCalibration::ToNominalThrust(hover_mix.command.thrust_N, thrust.lambda);
  dynamics.SetRotorThrustCommand(hover_mix.command);
  dynamics.SettleRotors();
  const double uncalibrated_torque = dynamics.RotorTorque_B().head<2>().norm();
  dynamics.SetRotorThrustCommand(calibrated);
  dynamics.SettleRotors();
  RecordProperty("roll_pitch_torque_uncalibrated_Nm", std::to_string(uncalibrated_torque));
  RecordProperty("roll_pitch_torque_calibrated_Nm",
                 std::to_string(dynamics.RotorTorque_B().head<2>().norm()));
  EXPECT_GT(uncalibrated_torque, 1e-2);
  EXPECT_LT(dynamics.RotorTorque_B().head<2>().norm(), 1e-3 * uncalibrated_torque);
  EXPECT_NEAR(dynamics.CollectiveThrust_mps2(), nominal.gravity_mps2, 0.05);
}

}  // namespace
}  // namespace aperture
