#pragma once
// Pose hold: holds a position + heading set-point from pose measurements of the vehicle (any
// source: the LED target seen by a ground camera, a gap or tag pose, motion capture) fused with
// the IMU, on hardware as in SITL (no ground truth, nothing from sim/).
//
//   IMU ──────────────┐
//   PoseMeasurement ──┴─> perception::PoseFusion (PoseImuFilter, the one start/restart policy)
//                              └─> estimate -> control::PositionController (Faessler thesis
//                                  (F.31)-(F.38), Table A.2 gains) on a constant reference
//                                  -> ThrustRatesCommand for the flight controller
//
// Initialization and restarts are PoseFusion's (perception/estimation/pose_fusion.h): the filter
// starts at the first pose measurement and restarts after max_consecutive_rejections outliers in
// a row with the velocity of the rejected run (an impulsive push the IMU missed leaves the old
// velocity estimate wrong). Until the first pose Step() commands nothing (Kind::kNone).
//
// Control law: the reference is the set-point with an acceleration feed-forward
//   a_ff = k_i * integral(p_set - p_est) - a_ext,
// (both terms clamped, anti-windup) which the PD law of (F.31) lacks:
//  * a_ext is the external (non-thrust, non-gravity) acceleration seen by the accelerometer,
//    a_ext = R_WB (f_B - b_a) - c_prev z_B with the previous collective-thrust command c_prev and
//    f_B the mean specific force of the IMU samples since the previous step (one sample would
//    alias the accelerometer's noise at the IMU rate into the reference: a noisy IMU made the
//    whole loop jitter at ~0.5 rad/s), low-passed with disturbance_time_constant_s: a
//    disturbance observer that cancels wind gusts (rotor drag on the airspeed, (F.2)) within
//    ~one time constant instead of letting them push the vehicle off until the PD law balances
//    them;
//  * the integral removes what is left in steady state (thrust-map and motor-lag errors).
// The position error seen by the PD law is clamped to max_position_error_m (bounded tilt after
// a push). Without a pose for longer than max_pose_age_s the hold continues on the IMU alone
// (dead reckoning; status() says so).
//
// Calling order (perception/autopilot.h): AddImu / AddPose as measurements are delivered (poses
// stamped at their measurement time, at most filter.history_duration_s old), Step(t_s) at the
// control rate. Bad parameters or non-finite inputs throw std::invalid_argument naming them.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "control/position_controller.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"
#include "perception/estimation/pose_fusion.h"
#include "perception/estimation/pose_imu_filter.h"

namespace aperture::planning {

struct PoseHoldParams {
  perception::PoseImuFilterParams filter;
  control::PositionControllerParams controller;  // Table A.2 gains
  // Integral gain [1/s^3]: with Table A.2's PD gains the closed loop s^3 + d s^2 + p s + k_i is
  // stable for k_i < d * p (= 20 horizontally); 3 settles a steady disturbance in ~2 s with
  // little overshoot. 0 disables the integral action.
  double integral_gain_per_s3 = 3.0;
  double max_integral_accel_mps2 = 2.0;  // anti-windup clamp of |a_i| [m/s^2]
  // Anti-windup: the error is clamped to this norm before it is integrated [m], so a push's
  // excursion (tens of cm) does not wind the integral up into an overshoot; steady offsets of a
  // few cm are integrated in full.
  double max_integrated_error_m = 0.05;
  // Low-pass time constant of the external-acceleration estimate a_ext [s]: ~10 control steps,
  // long against the motor lag (~20 ms, which makes c_prev differ from the thrust produced
  // during fast thrust changes), short against gusts. 0 disables the observer.
  double disturbance_time_constant_s = 0.1;
  double max_disturbance_accel_mps2 = 3.0;  // clamp of |a_ext| [m/s^2]
  double max_position_error_m = 1.0;     // PD error clamp: ~5 m/s^2, ~27 deg tilt at p_xy = 5
  double max_pose_age_s = 0.5;           // no pose for longer: status "dead reckoning"
  // Outliers in a row that restart the filter (>= 1): 3 LED frames at 40 Hz = 75 ms.
  int max_consecutive_rejections = 3;
  // The filter's process noise adapts to its residuals up to this factor (>= 1; 1: off;
  // perception::PoseFusion::AdaptProcessNoise): the hold is not told when its IMU is noisier than
  // specified. 100 covers densities ten times the specification.
  double max_process_noise_scale = 100.0;
  // Throws std::invalid_argument naming the field (negative gains, non-positive limits).
  void Validate() const;
};

struct PoseHoldSetpoint {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // position of B [m]
  double heading_rad = 0.0;                       // psi (trajectory_point.h)
};

class PoseHold {
 public:
  // `vehicle`: the controller's model (mass, drag). Throws for invalid parameters or set-point.
  PoseHold(const control::VehicleParameters& vehicle, const PoseHoldParams& params,
           const PoseHoldSetpoint& setpoint);

  void SetSetpoint(const PoseHoldSetpoint& setpoint);
  void AddImu(const perception::ImuSample& sample);
  // What became of the measurements processed by this call (PoseFusion::AddPose).
  std::vector<perception::PoseFusionOutcome> AddPose(const perception::PoseMeasurement& measurement);
  // Command for t_s (kThrustRates once a pose has initialized the filter, else kNone).
  perception::AutopilotCommand Step(double t_s);

  bool initialized() const { return fusion_.started(); }
  // The filter's estimate at its latest IMU sample; none before initialization.
  std::optional<perception::PoseImuEstimate> estimate() const;
  const PoseHoldSetpoint& setpoint() const { return setpoint_; }
  // Current integral feed-forward a_i [m/s^2].
  Eigen::Vector3d integral_accel_W() const;
  // Current external-acceleration estimate a_ext [m/s^2] (zero with the observer disabled).
  const Eigen::Vector3d& disturbance_accel_W() const { return disturbance_accel_W_; }
  double last_pose_t_s() const { return fusion_.last_pose_t_s(); }
  const perception::PoseFusionCounts& fusion_counts() const { return fusion_.counts(); }
  // "waiting for pose", "hold", "hold, dead reckoning 0.8 s".
  std::string status(double t_s) const;

 private:
  PoseHoldParams params_;
  PoseHoldSetpoint setpoint_;
  control::PositionController controller_;
  perception::PoseFusion fusion_;
  Eigen::Vector3d error_integral_W_ = Eigen::Vector3d::Zero();  // [m s]
  Eigen::Vector3d disturbance_accel_W_ = Eigen::Vector3d::Zero();  // a_ext [m/s^2]
  // Specific force of the IMU samples since the previous Step (their sum and count) [m/s^2].
  Eigen::Vector3d specific_force_sum_B_ = Eigen::Vector3d::Zero();
  int specific_force_count_ = 0;
  double last_collective_thrust_mps2_ = 0.0;  // c_prev; 0 before the first command
  double last_step_t_s_ = 0.0;
  bool stepped_ = false;
};

}  // namespace aperture::planning
