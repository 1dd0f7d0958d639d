#pragma once
// The GapFlyt mission (Sanket et al., RA-L 2018, seed 002) as a perception::Autopilot: fly through
// an opening of unknown shape, size and position with a forward monocular camera, the IMU and the
// downward range sensor only (no map, no known structure, nothing from sim/).
//
//   calibrate  hover thrust, zero body rates while the odometry averages the IMU biases at rest
//              (control/drag_aided_odometry.h); the odometry frame W starts here.
//   settle     position hold at the start for settle_s (the odometry's velocity settles).
//   scan       active vision (Sec. II, IV-A: "a fixed diagonal straight line trajectory in the
//              X_W - Z_W plane ... while taking a number of images"): a straight line along
//              scan_direction in the lateral/vertical plane (y_B, z_B of the start), heading held:
//              a minimum-jerk ramp to scan_speed_mps, a cruise at that constant velocity for
//              scan_cruise_s, a ramp back to rest. Only the cruise's frames go to the front ends
//              (the ts2p window of stack * stride + 1 frames centred on the cruise): at constant
//              velocity the attitude is constant (drag balance), so the stack holds the rotation-
//              free parallax TS²P assumes (Sec. II: Omega ~ 0) without derotation; one TS²P
//              detection (Sec. II). No detection (or an invalid one, or one whose opening runs
//              into the image border: the reference frame must show the whole gap, Sec. II): the
//              scan runs back the other way, up to max_scans times, then the mission aborts.
//   servo      label tracking (Sec. III, Alg. 1: gap_tracker) from the detection on, every frame;
//              the tracked contour C and safe point x_s (normalized, re-projected into the level
//              camera with the attitude estimate, servo/level_view.h) drive servo::GapServo
//              (`servo.law`): the moment servo towards the commit view (the detected contour
//              centred on the body axis's image and scaled to commit_area_fraction of the image,
//              at the nominal depth commit_depth_m: the opening's size is unknown, so a_n is the
//              depth up to the unknown scale and the goal is a view, not a distance), or the
//              paper's PID on x_s with the forward speed of theta_0 (Sec. III-B). Its body velocity
//              reference goes to the flatness/position controller (velocity tracking: the
//              position reference follows the estimate).
//              No commit after max_servo_s: the servo then holds the view (a hover on the image).
//   go_through (commit) when the tracked contour reaches commit_border_px of the image border (the
//              opening is about to fill the view) with the aimed line within
//              commit_max_aim_offset_m, the moment servo's error is below commit_error and still
//              (commit_max_error_rate), or the track is lost within commit_area_fraction's view
//              (same aim rule), and the odometry is not coasting through suspected wind: straight
//              along the heading at go_through_speed_mps for go_through_distance_m on the
//              odometry, on a line aimed through the last safe point (max_aim_correction_m).
//              Blind, as in the paper once the gap fills the view.
//   stop       position hold where go_through ended for stop_hold_s, then done.
//   aborted    no opening after max_scans scans, or the track lost before the commit (or at the
//              border with the aimed line out of reach): position hold where it happened (the
//              run ends on its duration).
//
// Front ends: `ts2p` (perception::Ts2pNode) and `gap_tracker` (perception::GapTrackerNode), the
// nodes `aperture run --frontends ts2p,gap_tracker` runs, hosted in a perception::FrontEndRunner.
// The ts2p interval is forced to "never again" (the tracker must not be re-initialized by a
// detection on the approach, whose flow is an expansion, not the scan's parallax).
// State estimate: control::DragAidedOdometry (attitude, range height, rotor-drag velocity); no
// PoseFusion: GapFlyt measures no pose. Times are on the sensor clock.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "control/drag_aided_odometry.h"
#include "control/gyro_attitude_hold.h"
#include "control/position_controller.h"
#include "control/quad_state.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"
#include "perception/camera/camera_model.h"
#include "perception/graph/front_end_runner.h"
#include "perception/ts2p/label_tracker.h"
#include "perception/ts2p/opening_track.h"
#include "perception/ts2p/ts2p_node.h"
#include "planning/motion_primitive.h"
#include "servo/gap_servo.h"

namespace aperture::planning {

struct GapflytMissionParams {
  int camera_id = 0;  // Frame::camera_id of the forward camera; other cameras are ignored
  double camera_rate_hz = 30.0;  // its frame rate: places the ts2p window on the scan [Hz]
  control::DragAidedOdometryParams odometry;
  control::PositionControllerParams controller;  // Table A.2 gains
  // Its interval is overridden (see above). Stride 3 (the node's default is 2): at scan_speed_mps
  // and 30 Hz the stack's baselines are 6-12 cm, and a small opening (a star, one 5 cm wider than
  // the vehicle) at 320 x 240 stands out of the wall's parallax; at stride 2 half the stars
  // rendered at 2.6 m gave no detection (tests/experiments/ts2p_detection_test.cc). The opening
  // flown is the detection's core at 0.6 of the way from B to F (ts2p_detector.h): at 0.8 alone
  // humps of wall beside triangles were taken for opening and flown into (docs/results/gapflyt.md).
  perception::Ts2pNodeParams ts2p = [] {
    perception::Ts2pNodeParams p;
    p.stride = 3;
    p.detector.core_threshold_fraction = 0.6;
    return p;
  }();
  perception::LabelTrackerParams tracker;
  // `servo.law`: moments | pid. The moment law's gain is raised from ViSP's drone defaults (1.5 /
  // 0.7 /s) to 2.0 / 1.2 /s: its error decays exponentially, and at 0.7 /s the ~1.5 m from the
  // scan to the commit view took ~8 s in SITL; at 1.2 /s the first reference (~0.8 m/s forward)
  // stays below max_servo_speed_mps.
  servo::GapServoParams servo = [] {
    servo::GapServoParams p;
    p.moments.gain.at_zero_per_s = 2.0;
    p.moments.gain.at_infinity_per_s = 1.2;
    return p;
  }();
  // Hold after the calibration [s]: the drag velocity's time constant (0.3 s) a few times over.
  double settle_s = 1.0;
  // Scan direction in the start's (y_B, z_B) plane (left, up; normalized): seed 002 Fig. 7's
  // diagonal.
  Eigen::Vector2d scan_direction = Eigen::Vector2d(1.0, 1.0);
  // Cruise speed [m/s]: 0.6 m/s at 30 Hz moves the camera 6 cm between frames three apart (the
  // ts2p stride), the ts2p bench's 5 cm scan step order.
  double scan_speed_mps = 0.6;
  // Ramps to and from the cruise [s]: the minimum-jerk ramp peaks at 1.875 v / T = 2.25 m/s^2.
  double scan_ramp_s = 0.5;
  // Cruise [s]: the ts2p window (4 * 3 + 1 frames = 0.4 s at 30 Hz) plus ~0.1 s on each side
  // for the attitude to settle after the ramp.
  double scan_cruise_s = 0.6;
  int max_scans = 3;
  // Moment law goal view: the detected contour centred on the body axis's image with this
  // fraction of the normalized image area (0.3: a 1.0 x 0.8 m opening ~0.95 m ahead with an 80
  // deg camera, where the label sets still hold their corners), at this nominal depth [m].
  double commit_area_fraction = 0.3;
  double commit_depth_m = 1.0;
  // Moment law: commit when |s - s*|_2 falls below this (a_n in the nominal depth's metres).
  // 0.1: the velocity estimate's bias (a few cm/s) holds the error at ~0.06 in SITL, where the
  // servo's reference no longer moves the vehicle.
  double commit_error = 0.1;
  // ... and the error has changed by less than commit_max_error_rate [1/s] (in the same units per
  // second: ~the relative velocity in m/s at the nominal depth) over the last commit_rate_window_s
  // [s]. After a 5 m/s gust the vehicle swung back through the goal view at 0.3-0.4 m/s sideways,
  // the error passed below commit_error on the way, and the blind line carried that motion into
  // the wall (`aperture bench faults`); the image, not the odometry (which a gust or a noisy IMU
  // leaves off by that much), says whether the vehicle is at rest in front of the opening.
  double commit_max_error_rate = 0.1;
  double commit_rate_window_s = 0.2;
  // Commit when the tracked contour comes within this many pixels of the image border while it
  // covers at least half the goal view's commit_area_fraction (a nearby opening filling the view).
  double commit_border_px = 4.0;
  // ... and the aimed line (through the safe point, see max_aim_correction_m) lies within this
  // distance of the vehicle [m]: a gust that pushed the vehicle aside also brings the opening to
  // the border, and committing there flew the line from 0.65 m off centre into the wall (SITL,
  // 2.5 m/s gusts); farther off, the servo goes on centring (or, if the track is lost there, the
  // mission aborts to a hover). max_aim_correction_m plus ~0.1 m the opening's margin absorbs.
  double commit_max_aim_offset_m = 0.35;
  // Longest servo phase before a commit [s]: it commits within 2-5 s in SITL (`aperture bench
  // gapflyt`); one that has not after 8 s (x10 IMU noise held the moment error above
  // commit_error for 12 s, and the commit came as the flight's time ran out) no longer commits
  // and holds on the servo: a hover on the image, which the odometry alone (its velocity drifting
  // at up to ~0.5 m/s with such noise) could not keep. A lost track then aborts to a position
  // hold on the odometry, as before.
  double max_servo_s = 8.0;
  // Speed limit of the servo's velocity reference [m/s] (the moment law's first steps are large).
  double max_servo_speed_mps = 1.2;
  // Rate limit of the servo's forward velocity reference [m/s^2]: the PID's forward speed (theta_0)
  // is a step, and the tilt a step in velocity asks for rotates the image faster than the label
  // tracker follows (the tracked contour blew up within 0.3 s in SITL); 1 m/s^2 (~6 deg of tilt)
  // reaches the PID's 1 m/s in 1 s.
  double max_servo_accel_mps2 = 1.0;
  double go_through_speed_mps = 1.0;
  // At the commit the blind line is aimed through the last tracked safe point, or where the
  // vehicle fits best in the tracked contour (footprint_placement.h) when that clears the edge by
  // over 1 cm more (a tight triangle only passes above its base): the safe point and the contour
  // are put on the wall through their level-view bearings and the wall's distance (TS²P's wall
  // parallax over the scan's mean baseline, minus the odometry's forward travel since); the line
  // moves sideways and vertically by at most this much [m] (0 = straight ahead from where the
  // vehicle committed, as the paper).
  double max_aim_correction_m = 0.25;
  // The vehicle's footprint in the opening's plane for that aim: body sphere and propeller disk
  // radii [m] (the rotor positions come from the vehicle parameters).
  double body_radius_m = 0.08;
  double propeller_radius_m = 0.0635;
  // Blind distance after the commit [m]: past a wall the commit view puts at ~0.6-1 m, short of a
  // background ~2 m behind it (seed 002: 0Z_B - 0Z_F ~ 3.1 m).
  double go_through_distance_m = 1.8;
  double stop_hold_s = 1.0;
  // Frames without a valid track before the commit that abort the mission (3 = 0.1 s at 30 Hz).
  int max_lost_frames = 3;

  // Throws std::invalid_argument naming the field (and via the components' Validate()).
  void Validate() const;
};

enum class GapflytPhase { kCalibrate, kSettle, kScan, kServo, kGoThrough, kStop, kDone, kAborted };
// "calibrate", "settle", "scan", "servo", "go_through", "stop", "done", "aborted".
const char* ToString(GapflytPhase phase);

// One servo step (for plots): the frame time, |s - s*| and the body velocity reference it gave.
struct GapflytServoSample {
  double t_s = 0.0;
  double error_norm = 0.0;
  Eigen::Vector3d v_B = Eigen::Vector3d::Zero();  // after the speed limit [m/s]
};

struct GapflytPhaseChange {
  double t_s = 0.0;
  GapflytPhase phase = GapflytPhase::kCalibrate;  // entered at t_s
};

class GapflytMission : public perception::Autopilot {
 public:
  // camera: the forward camera's model (normalizes the tracked pixels); T_BC its mount; vehicle:
  // the controller's model (its rotor drag d_x, d_y also feed the odometry and the PID's speed).
  // Throws std::invalid_argument for invalid params, a null camera or a non-rigid T_BC.
  GapflytMission(const GapflytMissionParams& params,
                 std::shared_ptr<const perception::CameraModel> camera,
                 const Eigen::Isometry3d& T_BC, const control::VehicleParameters& vehicle);

  std::string name() const override { return "gapflyt_mission"; }
  void OnImu(const perception::ImuSample& sample) override;
  void OnFrame(const perception::Frame& frame) override;
  void OnRange(const perception::RangeReading& reading) override;
  perception::AutopilotCommand Step(double t_s) override;
  // "<phase>" plus details, e.g. "scan 1/3", "servo (pid) |e| 0.021", "aborted: no opening".
  std::string status() const override;

  GapflytPhase phase() const { return phase_; }
  const std::vector<GapflytPhaseChange>& phase_changes() const { return phase_changes_; }
  const std::string& reason() const { return reason_; }  // why it aborted / committed
  control::QuadState estimate() const { return odometry_.estimate(); }
  servo::GapServoLaw law() const { return params_.servo.law; }
  int scans() const { return scans_; }
  // The TS²P detector's status of each scan's detection ("ok" or why there was no opening).
  const std::vector<std::string>& scan_statuses() const { return scan_statuses_; }
  int frames_tracked() const { return frames_tracked_; }
  // The detection the servo started from (null before).
  const std::shared_ptr<const perception::Ts2pDetection>& detection() const { return detection_; }
  // Sensor-clock time of that detection's reference frame, of the commit; NaN before.
  double detection_t_s() const { return detection_t_s_; }
  double commit_t_s() const { return commit_t_s_; }
  // Latest servo step (error, reference) while servoing.
  const std::optional<servo::ServoStepResult>& last_servo_step() const { return last_step_; }
  const std::vector<GapflytServoSample>& servo_trace() const { return servo_trace_; }
  // The aim correction applied at the commit (odometry frame) [m].
  const Eigen::Vector3d& aim_correction_W() const { return aim_correction_W_; }
  // The aimed line's offset from the vehicle at the commit before the cap (level body frame's
  // y_B, z_B; x = 0) [m]; nullopt before the commit or when it was unknown.
  const std::optional<Eigen::Vector3d>& commit_aim_offset_B() const { return commit_aim_offset_B_; }
  // Overlay of the latest processed frame: the front ends' (contour, safe point, F/B corners),
  // the FOE, the body axis's image and the phase.
  void DrawOverlay(cv::Mat& bgr) const;

 private:
  std::optional<perception::AutopilotCommand> StepCalibrate(double t_s);
  std::optional<perception::AutopilotCommand> StepSettle(double t_s);
  std::optional<perception::AutopilotCommand> StepScan(double t_s);
  std::optional<perception::AutopilotCommand> StepServo(double t_s);
  std::optional<perception::AutopilotCommand> StepGoThrough(double t_s);
  perception::AutopilotCommand StepHold(double t_s);  // stop, done, aborted

  void EnterPhase(GapflytPhase phase, double t_s);
  void Abort(const std::string& reason, double t_s);
  void StartScan(double t_s);
  void StartServo(const perception::Ts2pOutput& detection);
  void Commit(const std::string& reason, double t_s);
  // A frame of the servo phase: one servo step on the track.
  void ServoOnFrame(const perception::OpeningTrack& track);
  // The contour within commit_border_px of the image border while it covers half the goal view.
  bool TouchesBorder(const std::vector<Eigen::Vector2d>& contour_px) const;
  bool ReachesBorder(const std::vector<Eigen::Vector2d>& contour_px) const;  // border alone
  // Pixels -> normalized coordinates of the level camera (servo/level_view.h).
  std::optional<std::vector<Eigen::Vector2d>> LevelNormalized(
      const std::vector<Eigen::Vector2d>& px) const;
  perception::AutopilotCommand Track(const control::TrajectoryPoint& reference) const;
  perception::AutopilotCommand TrackBodyVelocity(double t_s, const Eigen::Vector3d& v_B) const;
  control::TrajectoryPoint HoldReference(double t_s) const;

  GapflytMissionParams params_;
  std::shared_ptr<const perception::CameraModel> camera_;
  Eigen::Isometry3d T_BC_;
  control::VehicleParameters vehicle_;
  control::DragAidedOdometry odometry_;
  control::PositionController controller_;
  control::GyroAttitudeHold attitude_hold_;  // calibrate: holds the start attitude on the gyro
  servo::GapServo servo_;
  std::unique_ptr<perception::FrontEndRunner> front_ends_;  // new for every scan

  GapflytPhase phase_ = GapflytPhase::kCalibrate;
  double phase_start_t_s_ = 0.0;
  std::vector<GapflytPhaseChange> phase_changes_;
  std::string reason_;
  bool servo_timed_out_ = false;  // max_servo_s ran out: servoing without a commit
  double heading_rad_ = 0.0;  // held throughout (odometry frame: 0)
  Eigen::Vector3d hold_p_W_ = Eigen::Vector3d::Zero();
  // The scan's ramp up, cruise, ramp down (each starting at its own t = 0).
  std::vector<MotionPrimitive> scan_segments_;
  double ScanDuration() const;
  control::TrajectoryPoint ScanReference(double t_rel) const;
  int scans_ = 0;
  std::vector<std::string> scan_statuses_;
  double scan_feed_start_t_s_ = 0.0;  // frames from here on go to the front ends
  bool detection_tried_ = false;      // the ts2p node reported its one detection of this scan
  std::shared_ptr<const perception::Ts2pDetection> detection_;
  double detection_t_s_ = std::numeric_limits<double>::quiet_NaN();
  double commit_t_s_ = std::numeric_limits<double>::quiet_NaN();
  bool desired_set_ = false;
  Eigen::Vector3d servo_v_B_ = Eigen::Vector3d::Zero();      // the servo's (limited) reference
  Eigen::Vector3d reference_v_B_ = Eigen::Vector3d::Zero();  // rate-limited towards servo_v_B_
  double last_servo_step_t_s_ = std::numeric_limits<double>::quiet_NaN();
  std::optional<servo::ServoStepResult> last_step_;
  std::vector<GapflytServoSample> servo_trace_;
  // The moment servo's recent errors (t_s, s - s*) over commit_rate_window_s.
  std::deque<std::pair<double, Eigen::VectorXd>> recent_errors_;
  std::optional<perception::OpeningTrack> last_track_;
  int lost_frames_ = 0;
  int frames_tracked_ = 0;
  Eigen::Vector3d go_through_start_W_ = Eigen::Vector3d::Zero();  // on the aimed line
  Eigen::Vector3d detection_p_W_ = Eigen::Vector3d::Zero();       // odometry at the detection
  Eigen::Vector3d aim_correction_W_ = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> commit_aim_offset_B_;
  // The line through the last tracked safe point (or where the footprint fits best), relative to
  // the vehicle in the level body frame (x = 0), uncapped; nullopt when unknown.
  std::optional<Eigen::Vector3d> AimOffsetB() const;
  // A commit at the border may fly: the aimed line within commit_max_aim_offset_m (or unknown).
  bool AimWithinReach() const;
  // No commit once max_servo_s ran out, nor while the odometry coasts through suspected wind.
  bool CommitAllowed() const;
  // Records the moment servo's error and says whether it stayed still over commit_rate_window_s.
  // Called only on frames whose error is below commit_error (and a commit allowed): the window
  // holds those frames, so a commit also needs half the window's worth of them.
  bool ErrorAtRest(double t_s, const Eigen::VectorXd& error);
  double last_imu_t_s_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace aperture::planning
