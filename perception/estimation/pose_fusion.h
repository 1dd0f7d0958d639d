#pragma once
// Pose fusion: the one path from a front end's PoseObservation (perception/pose_observation.h)
// to the pose + IMU filter (PoseImuFilter), with one start and restart policy. Every mission that
// flies on a pose front end (the gap mission, the LED hover, ...) goes through it.
//
//   PoseObservation (T_CX, covariance in C) --ToPoseMeasurement(rig)--> PoseMeasurement (T_WX')
//     --AddPose--> pending until the IMU has reached its time --> PoseImuFilter::Update
//
// The rig says how the observation relates to the vehicle (PoseObservation::fixed):
//   * fixed target X (gap, tags), camera on the body: the measured frame is C,
//       T_WC = T_WX * T_CX^-1, extrinsics T_BC;  rig = {T_W_fixed = T_WX, T_B_moving = T_BC};
//   * fixed camera C (LED ground camera), target on the body: the measured frame is X,
//       T_WX = T_WC * T_CX, extrinsics T_BX;     rig = {T_W_fixed = T_WC, T_B_moving = T_BX}.
// Covariance: the observation's left perturbation (pose_observation.h) maps to the filter's
// [n_p (W); n_theta (measured frame, right perturbation)] (pose_imu_filter.h):
//   fixed target:  cov_XC = control::InversePoseCovariance(T_CX, cov_CX) (left in X), then
//                  n_p = R_WX (dt - [p_XC]x dr), n_theta = R_CX dr;
//   fixed camera:  n_p = R_WC (dt - [p_CX]x dr), n_theta = R_XC dr
//                  (R_WC Exp(d) R_CX = R_WX Exp(R_XC d)),
// scaled by the rig's covariance_scale (a front end whose covariance model is optimistic on the
// vehicle's images is fused with an inflated one) and symmetrized.
//
// Start: the first AddPose starts the filter at that measurement (its time, the body pose it
// implies, zero velocity, the filter's initial sigmas) and replays the buffered IMU samples after
// it; a caller that must fix its world frame first (the gap mission) calls Start() itself and
// feeds poses only afterwards. Restart: after max_consecutive_rejections outliers in a row (the
// filter drifted on the IMU alone, or the pose source jumped) the filter starts again at the
// latest measurement, keeping its bias estimates, with the velocity of the rejected run (a least-
// squares fit to its body positions) when it differs from the previous estimate's by more than
// three of its standard errors (the vehicle was pushed, or the estimate diverged), else the
// previous velocity (a short run of noisy poses, e.g. 5 odometry poses of 2 cm at 50 Hz, fits a
// velocity to ~0.3 m/s only, and a restart on it jolts the controller). A restart
// that would turn the body by more than max_restart_rotation_rad from the IMU-propagated attitude
// is refused and the run forgotten: the gyro holds the attitude to a fraction of a degree over
// seconds, so such a run is a consistently wrong pose (a symmetric pattern labelled the other
// way round: a gap mission in a gust restarted on its gap turned by 180 deg and flew into the
// ground), not a vehicle that turned.
//
// Process-noise adaptation (off until AdaptProcessNoise): an IMU noisier than the filter's
// specification makes the filter overconfident, its residuals grow until the gate rejects runs of
// good poses and the filter restarts (a jump in the estimate the controller turns into a jolt).
// Covariance matching (Mehra 1972): a running mean m of d^2 / 6 (each d^2 capped at the gate, so
// one outlier weighs little; ~20 measurements) should be 1 for a consistent filter; every
// measurement multiplies the process-noise scale by m^0.2, bounded to [1, max_scale], so it
// settles where the residuals match their covariance. The scale survives restarts.
//
// Calling order (perception/autopilot.h): AddImu / AddPose as measurements are delivered; a pose
// stamped after the latest IMU sample waits for the IMU. Non-finite or non-rigid inputs throw
// std::invalid_argument naming them.
#include <Eigen/Geometry>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "control/quad_state.h"
#include "perception/estimation/pose_imu_filter.h"
#include "perception/pose_observation.h"
#include "perception/sensor_data.h"

namespace aperture::perception {

// Throws std::invalid_argument naming `name` unless T is finite with an orthonormal rotation of
// determinant +1 (tolerance 1e-6 on |R^T R - I|: calibration round-off passes, a scaled, sheared
// or reflected matrix does not).
void RequireRigid(const Eigen::Isometry3d& T, const std::string& name);

// How a stream's observations relate to the vehicle (see the header comment).
struct PoseRig {
  // T_WX of a fixed target or T_WC of a fixed camera: the fixed frame's pose in W.
  Eigen::Isometry3d T_W_fixed = Eigen::Isometry3d::Identity();
  // T_BC of the body camera (fixed target) or T_BX of the body-mounted target (fixed camera).
  Eigen::Isometry3d T_B_moving = Eigen::Isometry3d::Identity();
  double covariance_scale = 1.0;  // > 0; multiplies the mapped covariance
};

// The filter measurement of `observation` through `rig` (header comment). Throws
// std::invalid_argument when a transform is not finite and rigid (tolerance 1e-6 on R^T R = I,
// det +1), the covariance is missing or not finite, t_s is not finite, or the scale is not > 0.
PoseMeasurement ToPoseMeasurement(const PoseObservation& observation, const PoseRig& rig);

// `z_O`, a measurement in a frame O, in W: T_WX = T_WO * T_OX, its position noise rotated by
// R_WO (the rotation noise is in X already). Throws std::invalid_argument for a non-rigid T_WO.
PoseMeasurement InWorldFrame(const Eigen::Isometry3d& T_WO, const PoseMeasurement& z_O);

// The body pose a measurement implies, T_WB = T_WX * T_BX^-1: orientation q_WB and position p_WB.
Eigen::Quaterniond BodyOrientation(const PoseMeasurement& measurement);
Eigen::Vector3d BodyPosition(const PoseMeasurement& measurement);

struct PoseFusionParams {
  PoseImuFilterParams filter;
  // Outliers in a row that restart the filter (>= 1).
  int max_consecutive_rejections = 3;
  // Largest body rotation from the current attitude estimate a restart may make [rad] (> 0; pi:
  // no limit).
  double max_restart_rotation_rad = 0.5;
  void Validate() const;  // throws std::invalid_argument naming the field
};

// What became of one pose measurement.
struct PoseFusionOutcome {
  double t_s = 0.0;             // the measurement's time
  bool started_filter = false;  // it started (or restarted) the filter
  PoseUpdateResult update;      // the filter's result when it did not start it
};

struct PoseFusionCounts {
  int applied = 0;           // fused
  int rejected_outlier = 0;  // gated out
  int not_applied = 0;       // too old for the history (kTooOld)
  int starts = 0;            // first start + restarts
  int restarts = 0;          // restarts after max_consecutive_rejections outliers
  int restarts_refused = 0;  // runs whose restart would have turned the body too far
  int heights_applied = 0;   // height measurements fused (AddHeight)
  int heights_rejected = 0;  // height measurements gated out or older than the history
};

class PoseFusion {
 public:
  explicit PoseFusion(const PoseFusionParams& params);

  void AddImu(const ImuSample& sample);
  // Fuses `measurement` once the IMU has reached its time (now, if it has). Returns the outcomes
  // of the measurements processed by this call (this one and any that waited), in time order.
  std::vector<PoseFusionOutcome> AddPose(const PoseMeasurement& measurement);
  // A height measurement (e.g. a downward range sensor), fused once the IMU has reached its
  // time. It never starts or restarts the filter: before the start it is dropped, and a gated
  // one is only counted (heights_rejected).
  void AddHeight(const HeightMeasurement& measurement);
  // Starts the filter at `state` (its t_s), replaying the buffered IMU samples after it.
  void Start(const control::QuadState& state);
  // Starts (or starts again) at `initial`, biases and covariance included, replaying the buffered
  // IMU samples after its time; the buffer reaches filter.history_duration_s back from the latest
  // sample, so `initial` must not be older (throws std::invalid_argument, as for an invalid
  // estimate). Measurements older than `initial` are not applied. Process-noise scale and counts
  // are kept.
  void Start(const PoseImuEstimate& initial);

  bool started() const { return filter_ != nullptr; }
  // The filter's estimate at its latest IMU sample; none before the start.
  std::optional<PoseImuEstimate> estimate() const;
  // Time of the latest measurement fused or started from (< 0: none).
  double last_pose_t_s() const { return last_pose_t_s_; }
  const PoseFusionCounts& counts() const { return counts_; }
  // Adapt the process noise to the residuals from now on, up to max_scale (finite, >= 1; see the
  // header comment). Throws std::invalid_argument.
  void AdaptProcessNoise(double max_scale);
  // The filter's current process-noise scale (1 until adapted).
  double process_noise_scale() const { return process_noise_scale_; }
  const PoseFusionParams& params() const { return params_; }

 private:
  void Restart(const PoseMeasurement& measurement);
  void StartAt(const PoseImuEstimate& initial);  // Start without the age check
  // Least-squares velocity of the rejected run and its standard error per axis [m/s] (the
  // positions' mean variance over the spread of their times); nullopt for fewer than two times.
  std::optional<std::pair<Eigen::Vector3d, double>> RejectedRunVelocity() const;
  std::vector<PoseFusionOutcome> ApplyPending();
  // One step of the process-noise adaptation on a fused or gated measurement (header comment).
  void AdaptToResidual(const PoseUpdateResult& update);

  PoseFusionParams params_;
  std::unique_ptr<PoseImuFilter> filter_;
  std::deque<ImuSample> imu_buffer_;               // last filter.history_duration_s of IMU
  std::deque<PoseMeasurement> pending_;            // waiting for the IMU, in arrival order
  std::deque<HeightMeasurement> pending_heights_;  // the same for heights
  // The current run of rejected measurements: body positions and their position variances.
  struct RejectedPosition {
    double t_s = 0.0;
    Eigen::Vector3d p_WB = Eigen::Vector3d::Zero();
    double variance_m2 = 0.0;  // mean of the measurement's position variances
  };
  std::deque<RejectedPosition> rejected_p_WB_;
  int consecutive_rejections_ = 0;
  double last_pose_t_s_ = -1.0;
  PoseFusionCounts counts_;
  double max_process_noise_scale_ = 1.0;  // 1: no adaptation
  double process_noise_scale_ = 1.0;
  double mean_normalized_innovation_ = 1.0;  // running mean of min(d^2, gate) / 6
};

}  // namespace aperture::perception
