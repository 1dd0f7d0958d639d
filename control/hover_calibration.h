#pragma once
// Sensor-bias and thrust calibration in hover, Faessler thesis paper A, Section A.5.4,
// (A.17)-(A.29). Samples are collected while the vehicle hovers (the thesis uses 5 s of data);
// biases and thrust scales are then constants for the flight.
//
//  * Gyro bias (A.17)-(A.19): in hover omega = 0, so b_omega = mean(omega_meas).
//  * Accelerometer bias (A.20)-(A.22): in hover the specific force in B is the thrust
//    c z_B = g z_B (the thesis' "-g"), so b_acc = mean(f_meas_B) - g e_z (B frame; z up).
//  * Thrust scales (A.23)-(A.28): each rotor's true thrust is f_i = lambda_i f_check_i, with
//    f_check_i the thrust of the nominal map (G.3) at the applied command. In hover the torque is
//    zero and the mass-normalized thrust is g (A.27):
//        [ y_i ; -x_i ; s_i kappa_i ; 1/m ]_{i=1..4} diag(mean f_check) lambda = [0; 0; 0; g]
//    with rotor positions (x_i, y_i) and yaw signs s_i of (G.1) (the d = l/sqrt(2) matrix of (A.27)
//    for the X configuration) and kappa_i = kappa(mean f_check_i) of (G.5) (drag torque is a
//    function of the command, so it scales with lambda_i like the thrust).
//  * (A.29): a desired true thrust f_i,des is commanded as the nominal thrust f_i,des / lambda_i
//    (ToNominalThrust).
#include <optional>

#include <Eigen/Core>

#include "control/vehicle_parameters.h"

namespace aperture::control {

struct SensorBiases {
  Eigen::Vector3d gyro_bias_B = Eigen::Vector3d::Zero();   // b_omega (A.19) [rad/s]
  Eigen::Vector3d accel_bias_B = Eigen::Vector3d::Zero();  // b_acc (A.22) [m/s^2]
  int num_samples = 0;
};

struct ThrustCalibration {
  Eigen::Vector4d lambda = Eigen::Vector4d::Ones();               // lambda_i of (A.25)-(A.27)
  Eigen::Vector4d mean_nominal_thrust_N = Eigen::Vector4d::Zero();  // (A.28) [N]
  int num_samples = 0;
};

class HoverCalibration {
 public:
  // `vehicle` supplies m, g, rotor geometry and the nominal maps (its rotor_fitness is ignored:
  // lambda is what is being estimated). Throws std::invalid_argument if it is invalid.
  explicit HoverCalibration(const VehicleParameters& vehicle);

  // One raw IMU sample taken in hover (specific force [m/s^2], body rates [rad/s]).
  void AddImuSample(const Eigen::Vector3d& specific_force_B, const Eigen::Vector3d& omega_B);
  // Nominal rotor thrusts f_check_i,k [N]: the nominal map (G.3) at the applied commands (A.28).
  void AddNominalThrusts(const Eigen::Vector4d& nominal_thrust_N);

  // (A.19), (A.22); nullopt before the first IMU sample.
  std::optional<SensorBiases> ComputeSensorBiases() const;
  // (A.27), (A.28); nullopt without thrust samples or when (A.27) has no positive solution (the
  // samples were not taken in hover, e.g. a rotor reads zero thrust).
  std::optional<ThrustCalibration> ComputeThrustCalibration() const;

  // (A.29): nominal thrusts to command for desired true thrusts. Throws std::invalid_argument if
  // a lambda is not finite and > 0.
  static Eigen::Vector4d ToNominalThrust(const Eigen::Vector4d& desired_thrust_N,
                                         const Eigen::Vector4d& lambda);

  void Reset();

 private:
  VehicleParameters vehicle_;
  Eigen::Vector3d sum_specific_force_B_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_omega_B_ = Eigen::Vector3d::Zero();
  int num_imu_samples_ = 0;
  Eigen::Vector4d sum_nominal_thrust_N_ = Eigen::Vector4d::Zero();
  int num_thrust_samples_ = 0;
};

}  // namespace aperture::control
