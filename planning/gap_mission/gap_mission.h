#pragma once
// The narrow-gap mission of Falanga et al. 2017 (seed 000) as a perception::Autopilot that flies
// from camera images and IMU samples only (no ground truth, nothing from sim/):
//
//   detect    hover thrust, holding the attitude the vehicle had at its first IMU sample (gyro-
//             integrated; a vehicle that starts hovering stays level, so the specific force it
//             averages for gravity is gravity) until the gap detector has found the gap in
//             init_detections frames; the mission frame W is then fixed.
//   hover     position control on the filter estimate at the pose where the filter started,
//             until hover_s have passed and the position is known to init_max_relative_sigma
//             of the distance to the gap.
//   (plan)    one step: traverse (6) through the estimated gap, the approach candidate of lowest
//             cost (10) (planning/approach_planner.h) above the floor seen by the range sensor
//             (with fallback_limits if none passes approach.limits), a rest-to-rest transfer to
//             its start.
//   transfer  fly the transfer primitive (perception-aware heading (8)), then hold start_hold_s.
//   approach  track the approach primitive, replanned from the current estimate at every control
//             step (Sec. II-C, V-A: the previous primitive is kept when the replanned one is not
//             provably feasible, loses the gap from view or passes the traverse start on its way,
//             as a replan from a state a gust pushed towards the gap would; the position
//             controller then pushes back). It ends lead_in_s before the traverse start, on the
//             traverse's own arc (3)-(5) extended backwards in time.
//   lead_in   (beyond the paper) track that arc with position feedback for lead_in_s: a constant
//             acceleration reference lets the attitude and thrust settle after the approach's
//             final jerk, so the open-loop part starts on its initial conditions (3a), (3b).
//   traverse  open loop (Sec. II-A/B): constant collective thrust |<g, e3>| and the constant
//             attitude of the traverse (thrust along +-e3, the traverse heading), held from the
//             IMU-propagated attitude; no position feedback. Lasts the traverse's duration_s.
//   recover   the five-stage recovery of Faessler thesis paper B (control/recovery_state_machine.h)
//             down to position hold; after recovered_hold_s in the position stage (counted anew
//             from the odometry's alignment) the mission is done. The gap is behind the camera:
//             the filter carries on with the IMU until the downward camera's visual odometry
//             (OnOdometry; SVO in [12], emulated in SITL) has initialized,
//             recovery_odometry_delay_s after the recovery starts. Sec. II-F: "it has to recover
//             a vision-based state estimate" — the downward camera and the range sensor are used
//             solely in the recovery. Its poses, in its own frame O, are aligned
//             to the estimate over the first recovery_odometry_alignment_poses (T_WO = mean of
//             T_WB_est T_OB^-1: one pose would fix its own noise, 0.5 deg and 2 cm, into every
//             later residual, which the filter's gate then rejects) and fused from then on, the
//             filter started again at the first of them with its velocity sigma widened
//             (recovery_odometry_velocity_sigma_mps).
//             The range sensor's readings are fused as heights above the floor throughout the
//             recovery (recovery_range_sigma_m).
//   aborted   (from hover/transfer/approach when the gap is not detected for
//             detection_timeout_s, except in the approach's last approach_commit_s, or when
//             planning fails): straight to the recovery stages.
//
// Perception and state estimate: the `gap` front end (perception::GapNode, the node `aperture run
// --frontends gap` runs) inside a perception::FrontEndRunner; its pose observations (T_CG of the
// fixed gap) go through perception::ToPoseMeasurement with the rig {T_WG, T_BC,
// detection_covariance_scale} into perception::PoseFusion (PoseImuFilter with the one restart
// policy, latency handled by the filter), which the mission starts itself once W is fixed. Mission
// frame W (Sec. III: the state is estimated relative to the gap): origin at the gap centre, z_W up
// (gravity from the averaged accelerometer while hovering, expressed in G through the detections'
// R_CG), x_W the horizontal projection of the gap normal z_G (direction of traversal). The gap pose
// in W is therefore fixed, and TraverseTrajectory's gap frame G (x_G long side, z_G through the
// gap) is the detector's.
//
// Times are on the sensor clock (the simulator clock in SITL).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "control/gyro_attitude_hold.h"
#include "control/position_controller.h"
#include "control/quad_state.h"
#include "control/recovery_state_machine.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"
#include "perception/camera/camera_model.h"
#include "perception/estimation/pose_fusion.h"
#include "perception/estimation/pose_imu_filter.h"
#include "perception/gap/gap_detector.h"
#include "perception/graph/front_end_runner.h"
#include "planning/approach_planner.h"
#include "planning/motion_primitive.h"
#include "planning/traverse_trajectory.h"

namespace aperture::planning {

struct GapMissionParams {
  // Pattern geometry and detector settings; the sizes must be those of the real gap.
  perception::GapDetectorParams detector;
  perception::PoseImuFilterParams filter;  // set the IMU noise of the vehicle's IMU
  TraverseParameters traverse;
  // The planner's grid and cost with gentler feasibility limits than its defaults: the approach
  // is tracked with feedback on an estimate, so it keeps thrust (at most 14 m/s^2, 1.4 hover) and
  // body-rate (4 rad/s) margin for the feedback and the motors; at the planner's own 30 m/s^2 and
  // 10 rad/s the chosen approaches saturate rotors and arrive ~5 cm off in SITL. The minimum, 4
  // m/s^2, stays below the traverse thrust |<g, e3>| = g cos 45 deg cos 30 deg ~ 6 m/s^2 that
  // the approach ends with at the steepest gap of the acceptance range.
  ApproachPlannerParameters approach = [] {
    ApproachPlannerParameters p;
    p.limits.min_thrust_mps2 = 4.0;
    p.limits.max_thrust_mps2 = 14.0;
    p.limits.max_body_rate_radps = 4.0;
    return p;
  }();
  // Limits of a second planning attempt when no candidate passes approach.limits (steep gaps:
  // at 45 deg roll only these wider limits found an approach in SITL).
  FeasibilityLimits fallback_limits = [] {
    FeasibilityLimits limits;
    limits.min_thrust_mps2 = 2.0;
    limits.max_thrust_mps2 = 20.0;
    limits.max_body_rate_radps = 10.0;
    return limits;
  }();
  // Approach / transfer / hover tracking, with the rotor-lag feed-forward: the approach ends by
  // ramping the thrust from up to 20 m/s^2 down to the traverse's |<g, e3>| (~5 m/s^2 at 55 deg
  // roll) in ~0.3 s, and the lagging rotors' excess thrust alone put the vehicle 4-7 cm off
  // along the opening's 28 cm short side (SITL, 45-60 deg roll).
  control::PositionControllerParams controller = [] {
    control::PositionControllerParams p;
    p.compensate_rotor_lag = true;
    return p;
  }();
  control::RecoveryParams recovery;  // after the gap
  int camera_id = 0;  // Frame::camera_id of the forward camera; other cameras are ignored

  // Detections whose gravity direction is averaged to fix the mission frame (detection noise of
  // R_CG tilts W against gravity: 10 frames at 50 Hz average it down in 0.2 s of hover).
  int init_detections = 10;
  // The detector's covariance (pixel_sigma_px per edge sample, independent samples) is scaled by
  // this before fusion: rendered edges with noise, blur and aliasing err by more than the model
  // says, and an overconfident measurement model makes the filter gate out good detections.
  double detection_covariance_scale = 9.0;
  // After this many consecutive gated-out detections the filter restarts at the detected pose
  // (perception::PoseFusion's policy: biases kept, velocity from the rejected run; a diverged
  // filter otherwise rejects every later update).
  int max_consecutive_rejections = 5;
  // The approach stays this high above the ground [m], the ground being measured by the
  // downward range sensor while hovering (OnRange); without a range reading there is no floor.
  double min_ground_clearance_m = 0.5;
  // IMU samples averaged for the gravity direction while hovering before the first detection.
  int gravity_samples = 100;
  double hover_s = 0.5;  // filter convergence (biases) before planning [s]
  // Planning waits until the filter's position 1-sigma (position_sigma_m()) is below this
  // fraction of the estimated distance to the gap centre. Relative, because the detections'
  // position error grows with the distance (laterally: the gap's rotation error times the lever
  // arm), and because nothing flown from the hover needs more: the approach is replanned from
  // the estimate at every control step while the estimate sharpens on the way in, and the floor
  // keeps min_ground_clearance_m. 2 % = 10 cm at 5 m. The absolute 5 cm this replaced held the
  // vehicle ~8 s at 5 m (30 Hz camera, 30 deg roll): the scaled detection covariance there says
  // ~0.45 m laterally per frame, the camera positions actually scatter by ~7 cm.
  double init_max_relative_sigma = 0.02;
  // Transfer to the approach start: duration = max(min_transfer_s, 1.875 d / transfer_speed_mps)
  // (1.875 d / T is the peak speed of a rest-to-rest minimum-jerk primitive over distance d).
  double transfer_speed_mps = 3.0;
  double min_transfer_s = 1.0;
  double start_hold_s = 0.3;  // hover at the approach start before the approach [s]
  // Closed-loop lead-in along the traverse arc before the open-loop part [s]; 0 = none (paper).
  // Approaches that need fallback_limits fly none (GapMission::Plan says why).
  double lead_in_s = 0.2;
  // No replanning in the last part of the approach: the primitive is then too short to be
  // provably feasible anyway (Sec. V-A).
  double min_replan_remaining_s = 0.05;
  // Without a detection for this long before the approach's last approach_commit_s the mission
  // aborts [s]. In that last part the gap may leave the view (Sec. II intro) and the filter
  // carries on with the IMU: stopping there would hit the gap anyway.
  double detection_timeout_s = 0.5;
  double approach_commit_s = 1.0;
  // Time in the recovery's position stage before done [s]: long enough that the vehicle has
  // settled (the stage starts while attitude rates are still decaying).
  double recovered_hold_s = 2.0;
  // The recovery's visual odometry (OnOdometry) is fused from this long after the recovery
  // starts [s] (SVO initializes while the recovery levels the vehicle; [12], thesis B.3.2); a
  // delay beyond the flight (1e9): recover on the IMU alone.
  double recovery_odometry_delay_s = 1.0;
  // Odometry poses whose alignments T_WB_est T_OB^-1 are averaged into T_WO (>= 1): the mean of
  // N has 1/sqrt(N) of one pose's noise; 10 poses are 0.2 s of a 50 Hz odometry.
  int recovery_odometry_alignment_poses = 10;
  // At the alignment the filter starts again from its estimate at the first averaged pose with the
  // velocity sigma widened by this [m/s] (> 0; added in quadrature), and fuses the averaged poses:
  // the IMU-only recovery leaves it far surer of its velocity than it should be (SITL: sigma
  // ~1 cm/s against errors of 0.1-0.2 m/s with a vehicle that is not the model), so it gated the
  // odometry out as the position error grew, restarted, and the hold turned the jump into a jolt.
  double recovery_odometry_velocity_sigma_mps = 0.2;
  // In the recovery, each valid downward range reading taken within
  // recovery.max_tilt_for_height_rad of level is fused as the height above the floor measured
  // on the way to the gap (Sec. II-F: the range sensor is used in the recovery), with this sigma
  // [m]
  // (> 0; the simulated sensor's noise; +infinity: not fused). It bounds the IMU-only vertical
  // drift until the odometry is aligned.
  double recovery_range_sigma_m = 0.02;
  // Once the odometry is aligned, the filter's process noise adapts to its residuals up to this
  // factor (>= 1; 1: off; perception::PoseFusion::AdaptProcessNoise): the mission is not told
  // when its IMU is noisier than specified, and an overconfident filter gates good poses out,
  // restarts and jolts the hover. 100 covers densities ten times the specification.
  double recovery_max_process_noise_scale = 100.0;

  // Throws std::invalid_argument naming the field (and via the components' Validate()).
  void Validate() const;
};

enum class GapMissionPhase {
  kDetect,
  kHover,
  kTransfer,
  kApproach,
  kLeadIn,
  kTraverse,
  kRecover,
  kDone,     // recovered and holding position
  kAborted,  // recovering after an abort (see reason())
};
// "detect", "hover", "transfer", "approach", "lead_in", "traverse", "recover", "done",
// "aborted".
const char* ToString(GapMissionPhase phase);

struct GapMissionPhaseChange {
  double t_s = 0.0;
  GapMissionPhase phase = GapMissionPhase::kDetect;  // entered at t_s
};

class GapMission : public perception::Autopilot {
 public:
  // camera: the forward camera's model; T_BC its mount (p_B = T_BC * p_C); vehicle: the
  // controller's model. Throws std::invalid_argument for invalid params, a null camera or a
  // non-rigid T_BC.
  GapMission(const GapMissionParams& params, std::shared_ptr<const perception::CameraModel> camera,
             const Eigen::Isometry3d& T_BC, const control::VehicleParameters& vehicle);

  std::string name() const override { return "gap_mission"; }
  void OnImu(const perception::ImuSample& sample) override;
  void OnFrame(const perception::Frame& frame) override;
  // Frames of the mission's camera until the planned crossing (the phases only move on).
  bool WantsFrame(int camera_id, double t_s) const override;
  void OnRange(const perception::RangeReading& reading) override;
  // A body pose of the downward camera's visual odometry in its own gravity-aligned frame O
  // (X = B); used only in the recovery (see the header comment), ignored before.
  void OnOdometry(const perception::PoseMeasurement& pose_OB);
  perception::AutopilotCommand Step(double t_s) override;
  // "<phase>" plus details, e.g. "approach 1.2/2.0 s", "recover: horizontal_velocity".
  std::string status() const override;

  GapMissionPhase phase() const { return phase_; }
  const std::vector<GapMissionPhaseChange>& phase_changes() const { return phase_changes_; }
  // Why the mission aborted (empty otherwise).
  const std::string& reason() const { return reason_; }
  // The filter's state estimate in the mission frame (t_s = latest IMU sample); a default
  // QuadState (t_s = 0) before the filter starts.
  control::QuadState estimate() const;
  bool has_estimate() const { return fusion_.started(); }
  // The filter's position 1-sigma along its most uncertain axis of W [m]; NaN before the filter.
  double position_sigma_m() const;
  // Gap pose in the mission frame (fixed once the frame is set; identity rotation before).
  const GapPose& gap_W() const { return gap_W_; }
  // The traverse the vehicle flew (or is flying), in the mission frame; empty before.
  const std::optional<TraverseTrajectory>& traverse_plan() const { return traverse_; }
  // Sensor-clock time at which the open-loop traverse began; NaN before.
  double traverse_start_time_s() const { return traverse_start_t_s_; }
  // The estimate when the traverse began (what the open-loop traverse starts from); empty before.
  const std::optional<control::QuadState>& traverse_start_estimate() const {
    return traverse_start_estimate_;
  }
  // The approach as planned before the transfer (first primitive), empty before planning.
  const std::optional<ApproachCandidate>& approach_plan() const { return approach_; }
  // The transfer from the hover to the approach start (valid once planned, i.e. from kTransfer).
  const MotionPrimitive& transfer_plan() const { return transfer_; }
  // Time of the approach start (end of transfer and hold); NaN before.
  double approach_start_time_s() const { return approach_start_t_s_; }
  // Latest processed detection of the forward camera and its frame time (NaN before any).
  const perception::GapDetection& last_detection() const { return last_detection_; }
  // The front ends' overlays of the latest processed frame onto `bgr` (CV_8UC3, its size).
  void DrawOverlay(cv::Mat& bgr) const { front_ends_.DrawOverlays(bgr); }
  double last_detection_frame_time_s() const { return last_frame_t_s_; }
  int detections() const { return detections_; }
  int frames_processed() const { return frames_processed_; }
  int replans_accepted() const { return replans_accepted_; }
  int replans_rejected() const { return replans_rejected_; }
  // Detections the filter did not fuse (gated out or too old).
  int updates_rejected() const {
    return fusion_.counts().rejected_outlier + fusion_.counts().not_applied;
  }
  int filter_restarts() const { return fusion_.counts().restarts; }
  int filter_restarts_refused() const { return fusion_.counts().restarts_refused; }
  // The filter's counts (poses and the recovery's range heights fused, gated, restarts).
  const perception::PoseFusionCounts& fusion_counts() const { return fusion_.counts(); }
  // Visual-odometry poses handed to the filter in the recovery.
  int odometry_poses_fused() const { return odometry_poses_fused_; }
  // True when the approach was planned with fallback_limits (and then without a lead-in).
  bool used_fallback_limits() const { return used_fallback_limits_; }

 private:
  // One handler per phase: the command for t_s, or nullopt after a change of phase, whose
  // handler then runs at the same t_s (Step loops until one returns a command).
  std::optional<perception::AutopilotCommand> StepDetect(double t_s);
  std::optional<perception::AutopilotCommand> StepHover(double t_s);
  std::optional<perception::AutopilotCommand> StepTransfer(double t_s);
  std::optional<perception::AutopilotCommand> StepApproach(double t_s);
  std::optional<perception::AutopilotCommand> StepLeadIn(double t_s);
  std::optional<perception::AutopilotCommand> StepTraverse(double t_s);
  // kRecover, kDone and kAborted: the recovery state machine down to the position hold.
  perception::AutopilotCommand StepRecovery(double t_s);

  bool LookingForGap(double frame_t_s) const;
  // Before the filter: the gravity direction in G from this detection (mission frame set-up).
  void AccumulateUpInGap(const Eigen::Isometry3d& T_CG);
  void EnterPhase(GapMissionPhase phase, double t_s);
  void Abort(const std::string& reason, double t_s);
  void StartRecovery(double t_s);  // the recovery state machine, and the odometry's clock
  void StartFilter();
  void Plan(double t_s);
  // Lead-in of the planned approach: params_.lead_in_s, none with the fallback limits.
  double LeadInS() const { return used_fallback_limits_ ? 0.0 : params_.lead_in_s; }
  perception::AutopilotCommand Track(const control::TrajectoryPoint& reference) const;
  perception::AutopilotCommand HoverCommand() const;
  control::RecoveryInputs RecoveryInputsAt(double t_s) const;

  GapMissionParams params_;
  Eigen::Isometry3d T_BC_;
  control::VehicleParameters vehicle_;
  perception::FrontEndRunner front_ends_;
  ApproachPlanner approach_planner_;
  control::PositionController controller_;
  control::AttitudeController attitude_controller_;
  // Attitude relative to B0 (the body at the first IMU sample), integrated from the gyro until
  // the filter starts, and the detect phase's hover holding it.
  control::GyroAttitudeHold attitude_hold_;
  control::RecoveryStateMachine recovery_;

  GapMissionPhase phase_ = GapMissionPhase::kDetect;
  std::vector<GapMissionPhaseChange> phase_changes_;
  std::string reason_;

  // Before the filter: gravity direction (up) from the latest IMU samples, in B0 (the body at the
  // first IMU sample), and the sum of the up directions in G of the detections so far.
  std::vector<Eigen::Vector3d> recent_up_B0_;
  std::size_t recent_up_next_ = 0;
  Eigen::Vector3d up_G_sum_ = Eigen::Vector3d::Zero();
  std::optional<perception::ImuSample> last_imu_;
  Eigen::Isometry3d last_T_CG_ = Eigen::Isometry3d::Identity();  // latest before the filter (W)

  GapPose gap_W_;
  perception::PoseRig rig_;  // T_WG, T_BC and the detection covariance scale
  perception::PoseFusion fusion_;

  perception::GapDetection last_detection_;
  double last_frame_t_s_ = std::numeric_limits<double>::quiet_NaN();
  double last_detected_t_s_ = std::numeric_limits<double>::quiet_NaN();
  int detections_ = 0;
  int frames_processed_ = 0;
  int replans_accepted_ = 0;
  int replans_rejected_ = 0;
  bool used_fallback_limits_ = false;
  // The floor in W: a forgetting mean of (estimated height - range height) over the range
  // readings from the hover to the traverse (OnRange); the planner's floor and the recovery's.
  std::optional<double> floor_z_W_;
  int floor_samples_ = 0;
  double recovery_start_t_s_ = std::numeric_limits<double>::quiet_NaN();
  std::optional<Eigen::Isometry3d> T_WO_;  // the visual odometry's frame O in W, once aligned
  // Until then: the odometry poses received and the alignment T_WB_est T_OB^-1 each implies, and
  // the estimate when the first of them arrived.
  std::vector<std::pair<perception::PoseMeasurement, Eigen::Isometry3d>> odometry_alignments_;
  std::optional<perception::PoseImuEstimate> odometry_alignment_start_;
  int odometry_poses_fused_ = 0;

  double phase_start_t_s_ = 0.0;
  control::TrajectoryPoint hover_reference_;
  std::optional<TraverseTrajectory> traverse_;
  std::optional<ApproachCandidate> approach_;
  ApproachTarget approach_target_;
  MotionPrimitive transfer_;
  MotionPrimitive primitive_;  // current approach primitive
  double primitive_start_t_s_ = 0.0;
  double approach_start_t_s_ = std::numeric_limits<double>::quiet_NaN();
  double approach_end_t_s_ = 0.0;
  double traverse_start_t_s_ = std::numeric_limits<double>::quiet_NaN();
  std::optional<control::QuadState> traverse_start_estimate_;
  Eigen::Vector3d last_reference_a_W_ = Eigen::Vector3d::Zero();
  double position_stage_since_t_s_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace aperture::planning
