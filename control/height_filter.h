#pragma once
// Height filter of Faessler thesis paper B, Section B.2.6, (B.27)-(B.28): the height z above the
// ground and the vertical velocity z_dot (W, z up), from the downward distance sensor and the
// accelerometer, in a Kalman filter with a fixed gain K:
//   prediction (B.27), every IMU sample:  [z; z_dot] <- [1 dt; 0 1] [z; z_dot] + [dt^2/2; dt] a_z
//   update     (B.28), every range reading:  [z; z_dot] <- [z; z_dot] + K (z_meas - z)
// with a_z the vertical acceleration in W without gravity, (R_WB f_B)_z - g
// (VerticalAcceleration), and z_meas the range projected on z_W (HeightFromRange, flat ground).
//
// The thesis does not list K. By default it is the steady-state Kalman gain of this model for the
// configured noise levels and range period (ComputeSteadyStateGain); params.gain_K overrides it.
// Before Initialize() the filter has no estimate: Predict/Update throw std::logic_error.
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace aperture::control {

struct HeightEstimate {
  double z_m = 0.0;        // height above ground [m]
  double z_dot_mps = 0.0;  // vertical velocity [m/s]
  double time_since_init_s = 0.0;  // time propagated since Initialize() [s]
};

struct HeightFilterParams {
  // White noise of a_z [m/s^2]: rotor vibration on the accelerometer plus the projection error of
  // the IMU attitude estimate right after a throw (0.1 rad * g ~ 1 m/s^2). 2 m/s^2 also makes the
  // velocity converge from an unknown start within ~0.3 s (K = [0.13, 0.93] at 100 Hz), which the
  // recovery needs (RecoveryParams::min_height_filter_time_s); lower values smooth more but
  // converge slower (0.5 m/s^2: 0.53 s from a 3 m/s error).
  double accel_noise_sigma_mps2 = 2.0;
  double range_noise_sigma_m = 0.02;  // TeraRanger-One-class sensor (few cm; sim default)
  double range_period_s = 0.01;       // 100 Hz range readings
  double gravity_mps2 = 9.81;
  // Fixed gain K of (B.28); unset = steady-state gain from the three values above.
  std::optional<Eigen::Vector2d> gain_K;

  // Throws std::invalid_argument naming the field (non-positive sigmas, period or gravity,
  // non-finite gain).
  void Validate() const;
};

class HeightFilter {
 public:
  explicit HeightFilter(const HeightFilterParams& params = {});

  // Steady-state Kalman gain of (B.27)/(B.28) with piecewise-constant white acceleration noise
  // sigma_a over each range period dt and range noise sigma_r (discrete Riccati iteration).
  static Eigen::Vector2d ComputeSteadyStateGain(double range_period_s, double accel_sigma_mps2,
                                                double range_sigma_m);
  // a_z of (B.27): (R_WB f_B)_z - g for a (bias-corrected) specific force f_B.
  static double VerticalAcceleration(const Eigen::Quaterniond& q_WB,
                                     const Eigen::Vector3d& specific_force_B, double gravity_mps2);
  // Height of a sensor at the body origin looking along -z_B over flat ground:
  // range * (z_B . z_W). Returns nullopt when the sensor does not point downwards.
  static std::optional<double> HeightFromRange(double range_m, const Eigen::Quaterniond& q_WB);

  // Starts the estimate (B.3.2: when the distance sensor first points at the ground).
  void Initialize(double z_m, double z_dot_mps = 0.0);
  bool initialized() const { return initialized_; }
  // (B.27) over dt_s > 0 with vertical acceleration a_z [m/s^2].
  void Predict(double dt_s, double a_z_mps2);
  // (B.28) with a measured height [m].
  void Update(double z_meas_m);

  HeightEstimate estimate() const { return estimate_; }
  const Eigen::Vector2d& gain_K() const { return gain_K_; }

 private:
  HeightFilterParams params_;
  Eigen::Vector2d gain_K_;
  HeightEstimate estimate_;
  bool initialized_ = false;
};

}  // namespace aperture::control
