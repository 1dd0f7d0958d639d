#pragma once
// Drag-aided IMU odometry: the state estimate of a vehicle with a monocular camera that sees no
// known structure (GapFlyt, seed 002: "the Bebop 2 used its optical-flow position hold"), from the
// IMU and the downward range sensor only.
//
//   attitude  ImuAttitudeEstimator (Faessler thesis paper B, (B.22)-(B.26)), started level at
//             heading 0: the odometry frame W is the start pose's gravity-aligned heading frame;
//   height    HeightFilter (paper B, (B.27)-(B.28)) on the range sensor, z_W = height above the
//             ground, z_dot; readings off the prediction by max_range_innovation_m are rejected;
//   velocity  the rotor-drag model of the thesis (F.2): the thrust acts along z_B, so the
//             accelerometer's x_B, y_B components are the rotor drag alone,
//                 f_B,x = -d_x v_B,x,   f_B,y = -d_y v_B,y        (airspeed = velocity, no wind),
//             a direct measurement of the horizontal body velocity (Leishman et al., "Quadrotors
//             and accelerometers", IEEE CSM 2014). A complementary filter integrates the
//             acceleration R_WB f_B - g z_W (fast, drifting) and pulls its x_B, y_B components
//             towards -f_B,xy / d_xy with time constant velocity_time_constant_s (slow, unbiased
//             once the accelerometer bias is known); z_W velocity is the height filter's;
//   position  x_W, y_W integrated from the velocity (drifts with the velocity error: ~1 cm/s
//             with the default IMU), z_W the height.
//   biases    the gyro bias and the accelerometer's x_B, y_B bias are the means over the first
//             calibration_s of samples, taken at rest in hover (thesis (A.19), (A.22): at rest the
//             true f_B,xy is exactly zero, the thrust being along z_B); the estimate starts then.
//
//   wind      the drag measures airspeed, not ground velocity: a gust moves it by the wind speed
//             at once, while the integrated acceleration (which includes the gust's drag force)
//             does not jump. When the drag measurement's residual against the prediction,
//             low-passed over wind_residual_time_constant_s, exceeds the wind gate (the larger
//             of wind_gate_mps and wind_gate_sigmas standard deviations of that low-passed
//             residual, the noise taken from the calibration's accelerometer samples), the
//             velocity coasts on the integrated acceleration, for max_wind_coast_s at most: a
//             gust of a second passes without the estimate (and a controller on it) following
//             the air; a wind that stays is taken as velocity after that (it then drifts as
//             without the gate). The innovation gate with a timeout of navigation filters
//             (e.g. PX4's EKF2).
//   noise     the correction passes the accelerometer's white noise (density sigma_c) to the
//             velocity's derivative as white noise of density q_v / tau, q_v = sigma_c / d_y
//             (the drag velocity's noise), tau the velocity time constant; through a position
//             controller's velocity gain it becomes tilt-command rate: x10 the default IMU noise
//             at tau = 0.3 s makes a hover's roll/pitch rate jitter ~0.6 rad/s (x1: ~0.06). The
//             calibration measures sigma_c and lengthens tau to q_v / max_correction_noise when
//             that is longer (x10: ~1.5 s). A longer tau costs little: with an accelerometer bias
//             error b the velocity settles b (tau - 1 / d) off, smaller in size up to tau = 2 / d.
//
// Inputs in time order; Step-free: every IMU sample propagates. Throws std::invalid_argument for
// invalid params or non-finite / out-of-order samples.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

#include "control/height_filter.h"
#include "control/imu_attitude_estimator.h"
#include "control/quad_state.h"

namespace aperture::control {

struct DragAidedOdometryParams {
  // Its biases are replaced by the calibration. The accelerometer is a gravity sensor only on
  // average: a vehicle accelerating at a tilts the measured "up" by atan(a / g), and (B.25)'s
  // gate (|f| within 1 m/s^2 of g) passes every gentle lateral acceleration. At the thesis-like
  // 0.2 s time constant the tilt estimate follows those accelerations, hiding them from the
  // velocity prediction (the servo then sees a velocity lagging by ~0.3 s and oscillates). 5e-4
  // per sample at 500 Hz is a 4 s time constant: the calibrated gyro (bias known to ~1e-4 rad/s
  // after 0.5 s at rest: 0.1 deg in 15 s) carries the attitude through the manoeuvres, the
  // accelerometer only removes the slow drift.
  ImuAttitudeEstimatorParams attitude = [] {
    ImuAttitudeEstimatorParams p;
    p.correction_gain = 5e-4;
    return p;
  }();
  HeightFilterParams height;
  // d_x, d_y of (F.2) [1/s] (VehicleParameters::rotor_drag_D_per_s); both must be > 0.
  Eigen::Vector2d rotor_drag_xy_per_s = Eigen::Vector2d(0.5, 0.35);
  // Complementary-filter time constant of the drag measurement [s]: the accelerometer's white
  // noise (3.9e-3 m/s^2/sqrt(Hz) by default) divided by d_y = 0.35 is ~1.1e-2 m/s/sqrt(Hz), which
  // 0.3 s smooths to ~1 cm/s; long against the motor lag that makes f_B,xy lag the thrust tilt
  // during fast manoeuvres, short against the drift of the integrated acceleration.
  double velocity_time_constant_s = 0.3;
  // The largest density of the correction's noise in the velocity's derivative (see above)
  // [m/s^2/sqrt(Hz)]: 2x the default IMU's (3.9e-3 / 0.35 / 0.3 = 0.037); 1e9 keeps tau fixed.
  double max_correction_noise = 0.075;
  // Duration of the bias calibration at rest before the estimate starts [s].
  double calibration_s = 0.5;
  // The wind gate (see above). The residual's time constant [s]: 0.1 s keeps the default IMU's
  // noise at ~2 cm/s there while a 2.5 m/s gust crosses the gate in ~20 ms. The gate's floor
  // [m/s]: above the residual the motor lag makes in the mission's accelerations (~0.3 m/s at
  // ~2 m/s^2, drag_aided_odometry_sim_test.cc); 1e9 turns the gate off. The noise factor: a
  // noisier IMU raises the gate (x10 the default noise: ~0.9 m/s). The longest coast [s].
  double wind_residual_time_constant_s = 0.1;
  double wind_gate_mps = 0.4;
  double wind_gate_sigmas = 5.0;
  double max_wind_coast_s = 1.5;
  // Range readings whose height differs from the predicted one by more than this are rejected
  // [m]: the ray hit something above the ground (crossing a wall, the ray grazes the opening's
  // lower edge and reads the wall's height: a 1 m step the filter would chase). 0.3 m is 15
  // sigma of the sensor's 2 cm noise and ~0.5 s of the height filter's worst drift.
  double max_range_innovation_m = 0.3;
  // Throws std::invalid_argument naming the field.
  void Validate() const;
};

class DragAidedOdometry {
 public:
  explicit DragAidedOdometry(const DragAidedOdometryParams& params);

  void AddImu(double t_s, const Eigen::Vector3d& specific_force_B, const Eigen::Vector3d& omega_B);
  // A valid downward range reading [m] (along -z_B from B over flat ground).
  void AddRange(double range_m);

  // True once calibrated and a range reading has set the height.
  bool started() const { return started_; }
  // The estimate at the latest IMU sample (default QuadState before started()).
  QuadState estimate() const;
  const Eigen::Vector3d& gyro_bias_B() const { return gyro_bias_B_; }
  const Eigen::Vector2d& accel_bias_xy_B() const { return accel_bias_xy_B_; }
  int ranges_rejected() const { return ranges_rejected_; }
  // The wind gate in use [m/s] (after the calibration) and whether the latest sample's velocity
  // coasted (false once max_wind_coast_s has run out).
  double wind_gate_mps() const { return wind_gate_mps_; }
  bool coasting() const { return coasting_; }
  // The velocity time constant in use [s] (after the calibration).
  double velocity_time_constant_s() const { return velocity_time_constant_s_; }

 private:
  void Calibrate(double t_s, const Eigen::Vector3d& f_B, const Eigen::Vector3d& omega_B);
  void Propagate(double t_s, const Eigen::Vector3d& f_B, const Eigen::Vector3d& omega_B);

  DragAidedOdometryParams params_;
  ImuAttitudeEstimator attitude_;
  HeightFilter height_;
  // Calibration sums.
  std::optional<double> first_t_s_;
  int calibration_samples_ = 0;
  Eigen::Vector3d omega_sum_B_ = Eigen::Vector3d::Zero();
  Eigen::Vector2d f_xy_sum_B_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d f_xy_squares_B_ = Eigen::Vector2d::Zero();  // sum of squares
  bool calibrated_ = false;
  bool started_ = false;
  std::optional<double> last_range_m_;
  int ranges_rejected_ = 0;
  Eigen::Vector3d gyro_bias_B_ = Eigen::Vector3d::Zero();
  Eigen::Vector2d accel_bias_xy_B_ = Eigen::Vector2d::Zero();
  double t_s_ = 0.0;
  Eigen::Vector3d p_W_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_W_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d omega_hat_B_ = Eigen::Vector3d::Zero();
  double wind_gate_mps_ = 0.0;
  Eigen::Vector2d residual_lp_B_ = Eigen::Vector2d::Zero();  // drag velocity - prediction
  double coast_s_ = 0.0;                                     // of the current coast
  bool coasting_ = false;
  double velocity_time_constant_s_ = 0.0;
};

}  // namespace aperture::control
