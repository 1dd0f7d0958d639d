#pragma once
// The on-board recovery chain of Faessler thesis paper B wired together, for an autopilot fed
// with raw sensor data: IMU samples drive the launch detector (B.29), the IMU attitude estimator
// (B.22)-(B.26) and the height filter prediction (B.27); range readings drive the height filter
// update (B.28); the five-stage RecoveryStateMachine (B.3.2) turns the estimates into a
// ThrustRatesCommand for the low-level body-rate loop and mixer.
//
// Glue it adds: the height filter is initialized with the first usable range reading after the
// state machine asks for it (end of stage 1), with z_dot = 0; range readings are projected with
// the current attitude estimate (HeightFilter::HeightFromRange); the accelerometer bias of the
// attitude params is removed before the height prediction. Restart() begins a recovery without a
// throw (state-estimation failure, B.3 intro): the machine enters the attitude stage at once.
#include <optional>

#include <Eigen/Core>

#include "control/commands.h"
#include "control/height_filter.h"
#include "control/imu_attitude_estimator.h"
#include "control/launch_detector.h"
#include "control/quad_state.h"
#include "control/recovery_state_machine.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {

struct RecoveryPipelineParams {
  ImuAttitudeEstimatorParams attitude;  // set gyro/accel biases from HoverCalibration
  HeightFilterParams height;
  // Launch detection; its idle thrust is taken from the vehicle when left unset.
  std::optional<LaunchDetectorParams> launch;
  RecoveryParams recovery;
};

class RecoveryPipeline {
 public:
  // Throws std::invalid_argument for invalid vehicle parameters or params.
  explicit RecoveryPipeline(const VehicleParameters& vehicle,
                            const RecoveryPipelineParams& params = {});

  // Raw IMU sample (t_s strictly increasing): specific force [m/s^2], body rates [rad/s].
  void AddImu(double t_s, const Eigen::Vector3d& specific_force_B, const Eigen::Vector3d& omega_B);
  // A valid downward range reading [m] (skip invalid ones). Ignored while the sensor does not
  // point downwards according to the attitude estimate or before the height filter is requested.
  void AddRange(double range_m);
  // The vision estimate (p_WB, v_W) once the vision pipeline is initialized; nullopt before.
  void SetVisionState(const std::optional<QuadState>& vision_state) { vision_state_ = vision_state; }

  // One control step at t_s with the latest estimates (see RecoveryStateMachine::Step).
  RecoveryOutput Step(double t_s);
  // Recovery without a throw at t_s: the next Step() runs the attitude stage. The height filter
  // and the vision state are dropped.
  void Restart(double t_s);

  const ImuAttitudeEstimator& attitude() const { return attitude_; }
  const HeightFilter& height_filter() const { return height_; }
  const LaunchDetector& launch_detector() const { return launch_; }
  const RecoveryStateMachine& state_machine() const { return machine_; }

 private:
  RecoveryPipelineParams params_;
  LaunchDetector launch_;
  ImuAttitudeEstimator attitude_;
  HeightFilter height_;
  RecoveryStateMachine machine_;
  std::optional<QuadState> vision_state_;
  bool height_filter_requested_ = false;
  bool has_imu_time_ = false;
  double last_imu_t_s_ = 0.0;
};

}  // namespace aperture::control
