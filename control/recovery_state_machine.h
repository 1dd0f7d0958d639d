#pragma once
// Five-stage recovery after a throw or a state-estimation failure, Faessler thesis paper B,
// Section B.3 / B.3.2. Each stage uses the controller of B.2 (attitude controller (B.10)-(B.20),
// position controller (B.8) = PositionController) with some gains set to zero:
//
//  0 kWaitingForLaunch   rotors idle (c = 0, omega = 0) until the launch detector fires (B.29).
//  1 kAttitude           level the vehicle: attitude controller towards z_des = z_W, fixed
//                        c = g (no height information yet).
//      -> 2 when the tilt (angle z_B, z_W) < 20 deg and |omega^(x,y)| < 10 rad/s; the height filter
//           is to be initialized now (RecoveryOutput::initialize_height_filter).
//  2 kVerticalVelocity   (B.8) with P_pos = 0 and d_xy = 0: vertical velocity to zero.
//      -> 3 when |z_dot| < 0.3 m/s; the current height becomes the reference height.
//  3 kHeight             (B.8) with p_xy = d_xy = 0: hold the reference height; the vehicle
//                        drifts horizontally, which initializes the vision pipeline.
//      -> 4 when the vision state estimate is available (RecoveryInputs::vision_state).
//  4 kHorizontalVelocity (B.8) with p_xy = 0: horizontal velocity to zero.
//      -> 5 when |v^(x,y)| < 0.2 m/s; the current position and heading are locked.
//  5 kPosition           full (B.8) on the locked position and heading until a new mission.
//
// Note on stage 2: the thesis text says "control the horizontal velocity to zero ... set P_pos and
// the vertical velocity gain d_xy to zero"; d_xy is the horizontal velocity gain and the stage is
// named "Attitude and Vertical Velocity Control" (and only the vertical velocity is observable
// then), so the vertical velocity is controlled with d_z and P_pos = d_xy = 0.
//
// Stepping: Step() computes the command of the current stage, then evaluates that stage's exit
// condition and advances by at most one stage, so every stage appears in order in transitions().
// A stage whose exit condition already holds on entry lasts one step (the thesis' "skipped
// entirely" for stages 1, 2 and 4). Heading: until stage 5 the heading reference is the current
// heading (no yaw control); stage 5 locks it. Attitude and body rates always come from the
// inputs (the IMU estimator); height and vertical velocity from the height filter in stages 2-3;
// position and velocity from the vision estimate in stages 4-5.
//
// Beyond the thesis: the exit of stage 2 also requires the height filter to have run for
// min_height_filter_time_s, because the filter starts with an unknown vertical velocity (0) and
// would otherwise pass |z_dot| < 0.3 m/s on its initial guess. Set it to 0 for the bare thesis.
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "control/attitude_controller.h"
#include "control/commands.h"
#include "control/height_filter.h"
#include "control/position_controller.h"
#include "control/quad_state.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {

enum class RecoveryStage {
  kWaitingForLaunch = 0,
  kAttitude = 1,
  kVerticalVelocity = 2,
  kHeight = 3,
  kHorizontalVelocity = 4,
  kPosition = 5,
};
// "waiting_for_launch", "attitude", "vertical_velocity", "height", "horizontal_velocity",
// "position" (for logs and CSV).
const char* ToString(RecoveryStage stage);

struct RecoveryParams {
  double max_tilt_for_height_rad = 20.0 * 3.14159265358979323846 / 180.0;  // stage 1 -> 2 (B.3.2)
  double max_roll_pitch_rate_radps = 10.0;   // |omega^(x,y)|, stage 1 -> 2 (B.3.2)
  double max_vertical_speed_mps = 0.3;       // |z_dot|, stage 2 -> 3 (B.3.2)
  double max_horizontal_speed_mps = 0.2;     // |v^(x,y)|, stage 4 -> 5 (B.3.2)
  // Not in the thesis (see header comment). With the default HeightFilter gain a 3 m/s initial
  // velocity error falls below 0.3 m/s in 0.27 s.
  double min_height_filter_time_s = 0.3;
  // Gains of (B.8) and of the attitude controller; Table A.2 defaults. Stages 2-4 zero some of
  // them as listed above.
  PositionControllerParams controller;

  // Throws std::invalid_argument naming the field (negative or non-finite thresholds, invalid
  // controller gains).
  void Validate() const;
};

struct RecoveryInputs {
  double t_s = 0.0;
  bool launch_detected = false;                                   // LaunchDetector (B.29)
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();       // ImuAttitudeEstimator (B.2.5)
  Eigen::Vector3d omega_B = Eigen::Vector3d::Zero();              // bias-corrected gyro [rad/s]
  std::optional<HeightEstimate> height;                           // HeightFilter once initialized
  std::optional<QuadState> vision_state;  // p_WB, v_W once the vision pipeline is initialized
};

struct RecoveryOutput {
  RecoveryStage stage = RecoveryStage::kWaitingForLaunch;  // stage that computed `command`
  ThrustRatesCommand command;
  // True on the step that enters stage 2: initialize the height filter before the next Step().
  bool initialize_height_filter = false;
};

struct RecoveryTransition {
  double t_s = 0.0;
  RecoveryStage from = RecoveryStage::kWaitingForLaunch;
  RecoveryStage to = RecoveryStage::kWaitingForLaunch;
};

class RecoveryStateMachine {
 public:
  // Throws std::invalid_argument for invalid vehicle parameters or params.
  explicit RecoveryStateMachine(const VehicleParameters& vehicle, const RecoveryParams& params = {});

  // One control step. While `height` is missing in stages 2-3 (filter not yet initialized) the
  // stage-1 command is applied and the stage does not advance. Throws std::invalid_argument when
  // `vision_state` is missing in stages 4-5 (a lost vision estimate means: Reset() and recover
  // again) or an input is not finite, naming it.
  RecoveryOutput Step(const RecoveryInputs& inputs);

  RecoveryStage stage() const { return stage_; }
  // Time of the step that entered the current stage [s].
  double stage_entry_time_s() const { return stage_entry_t_s_; }
  const std::vector<RecoveryTransition>& transitions() const { return transitions_; }
  // Reference height of stage 3 (set on entering it) [m].
  double reference_height_m() const { return reference_height_m_; }
  // Position and heading locked on entering stage 5 (vision frame).
  const Eigen::Vector3d& locked_position_W() const { return locked_position_W_; }
  double locked_heading_rad() const { return locked_heading_rad_; }
  // Back to kWaitingForLaunch with no transitions.
  void Reset();
  // Recovery without a throw (state-estimation failure, B.3 intro): Reset(), then enter the
  // attitude stage at t_s (recorded as the transition 0 -> 1), so the next Step() levels the
  // vehicle instead of idling the rotors.
  void StartWithoutLaunch(double t_s);

 private:
  ThrustRatesCommand ComputeCommand(const RecoveryInputs& inputs) const;
  bool ExitConditionHolds(const RecoveryInputs& inputs) const;
  void Advance(const RecoveryInputs& inputs);

  VehicleParameters vehicle_;
  RecoveryParams params_;
  AttitudeController attitude_controller_;
  PositionController vertical_velocity_controller_;    // stage 2
  PositionController height_controller_;               // stage 3
  PositionController horizontal_velocity_controller_;  // stage 4
  PositionController position_controller_;             // stage 5
  RecoveryStage stage_ = RecoveryStage::kWaitingForLaunch;
  double stage_entry_t_s_ = 0.0;
  double reference_height_m_ = 0.0;
  double reference_z_vision_m_ = 0.0;  // stage 4 vertical reference in the vision frame
  Eigen::Vector3d locked_position_W_ = Eigen::Vector3d::Zero();
  double locked_heading_rad_ = 0.0;
  std::vector<RecoveryTransition> transitions_;
};

}  // namespace aperture::control
