#include "planning/gapflyt/gapflyt_mission.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "control/require.h"
#include "perception/ts2p/gap_tracker_node.h"
#include "planning/body_velocity_tracking.h"
#include "planning/gapflyt/footprint_placement.h"
#include "servo/level_view.h"
#include "servo/polygon_moments.h"

namespace aperture::planning {
namespace {

// The ts2p node's interval that never comes: one detection per scan (see the header).
constexpr int kOneDetectionPerScan = 1 << 30;
// The aim leaves the safe point for the footprint's best placement only when that clears the
// edge by this much more [m].
constexpr double kAimClearanceGainM = 0.01;

cv::Point ToPoint(const Eigen::Vector2d& p) {
  return {static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))};
}

}  // namespace

void GapflytMissionParams::Validate() const {
  control::RequireAtLeast(camera_id, 0, "GapflytMissionParams.camera_id");
  control::RequirePositive(camera_rate_hz, "GapflytMissionParams.camera_rate_hz");
  odometry.Validate();
  controller.Validate();
  ts2p.Validate();
  tracker.Validate();
  servo.Validate();
  control::RequireNonNegative(settle_s, "GapflytMissionParams.settle_s");
  control::RequireFinite(scan_direction, "GapflytMissionParams.scan_direction");
  control::Require(scan_direction.norm() > 0.0, "GapflytMissionParams.scan_direction",
                   "must not be zero: the scan's parallax is what TS2P detects");
  control::RequirePositive(scan_speed_mps, "GapflytMissionParams.scan_speed_mps");
  control::RequirePositive(scan_ramp_s, "GapflytMissionParams.scan_ramp_s");
  control::RequirePositive(scan_cruise_s, "GapflytMissionParams.scan_cruise_s");
  control::Require(scan_cruise_s * camera_rate_hz >= ts2p.stack * ts2p.stride,
                   "GapflytMissionParams.scan_cruise_s", scan_cruise_s,
                   "must hold the ts2p window (stack * stride frame periods)");
  control::RequireAtLeast(max_scans, 1, "GapflytMissionParams.max_scans");
  control::RequireInRange(commit_area_fraction, 0.01, 1.0,
                          "GapflytMissionParams.commit_area_fraction");
  control::RequirePositive(commit_depth_m, "GapflytMissionParams.commit_depth_m");
  control::RequirePositive(commit_error, "GapflytMissionParams.commit_error");
  control::RequirePositive(commit_max_error_rate, "GapflytMissionParams.commit_max_error_rate");
  control::RequirePositive(commit_rate_window_s, "GapflytMissionParams.commit_rate_window_s");
  control::RequireNonNegative(commit_border_px, "GapflytMissionParams.commit_border_px");
  control::RequireNonNegative(commit_max_aim_offset_m,
                              "GapflytMissionParams.commit_max_aim_offset_m");
  control::RequirePositive(max_servo_s, "GapflytMissionParams.max_servo_s");
  control::RequirePositive(max_servo_speed_mps, "GapflytMissionParams.max_servo_speed_mps");
  control::RequirePositive(max_servo_accel_mps2, "GapflytMissionParams.max_servo_accel_mps2");
  control::RequirePositive(go_through_speed_mps, "GapflytMissionParams.go_through_speed_mps");
  control::RequireNonNegative(max_aim_correction_m, "GapflytMissionParams.max_aim_correction_m");
  control::RequireNonNegative(body_radius_m, "GapflytMissionParams.body_radius_m");
  control::RequireNonNegative(propeller_radius_m, "GapflytMissionParams.propeller_radius_m");
  control::RequirePositive(go_through_distance_m, "GapflytMissionParams.go_through_distance_m");
  control::RequireNonNegative(stop_hold_s, "GapflytMissionParams.stop_hold_s");
  control::RequireAtLeast(max_lost_frames, 1, "GapflytMissionParams.max_lost_frames");
}

const char* ToString(GapflytPhase phase) {
  switch (phase) {
    case GapflytPhase::kCalibrate:
      return "calibrate";
    case GapflytPhase::kSettle:
      return "settle";
    case GapflytPhase::kScan:
      return "scan";
    case GapflytPhase::kServo:
      return "servo";
    case GapflytPhase::kGoThrough:
      return "go_through";
    case GapflytPhase::kStop:
      return "stop";
    case GapflytPhase::kDone:
      return "done";
    case GapflytPhase::kAborted:
      return "aborted";
  }
  return "unknown";
}

namespace {

GapflytMissionParams Checked(GapflytMissionParams params,
                             const std::shared_ptr<const perception::CameraModel>& camera,
                             const control::VehicleParameters& vehicle) {
  if (!camera) throw std::invalid_argument("GapflytMission: the camera model is null");
  params.ts2p.interval = kOneDetectionPerScan;
  params.odometry.rotor_drag_xy_per_s = vehicle.rotor_drag_D_per_s.head<2>();
  params.odometry.attitude.gravity_mps2 = vehicle.gravity_mps2;
  params.odometry.height.gravity_mps2 = vehicle.gravity_mps2;
  params.Validate();
  return params;
}

}  // namespace

GapflytMission::GapflytMission(const GapflytMissionParams& params,
                               std::shared_ptr<const perception::CameraModel> camera,
                               const Eigen::Isometry3d& T_BC,
                               const control::VehicleParameters& vehicle)
    : params_(Checked(params, camera, vehicle)),
      camera_(std::move(camera)),
      T_BC_(T_BC),
      vehicle_(vehicle),
      odometry_(params_.odometry),
      controller_(vehicle, params_.controller),
      attitude_hold_(params_.controller.attitude),
      servo_(params_.servo, T_BC, vehicle.rotor_drag_D_per_s.x()) {
  phase_changes_.push_back({0.0, phase_});
}

void GapflytMission::EnterPhase(GapflytPhase phase, double t_s) {
  phase_ = phase;
  phase_start_t_s_ = t_s;
  phase_changes_.push_back({t_s, phase});
}

void GapflytMission::Abort(const std::string& reason, double t_s) {
  reason_ = reason;
  hold_p_W_ = estimate().p_WB;
  EnterPhase(GapflytPhase::kAborted, t_s);
}

void GapflytMission::OnImu(const perception::ImuSample& sample) {
  if (!odometry_.started()) attitude_hold_.AddImu(sample.t_s, sample.omega_B);
  odometry_.AddImu(sample.t_s, sample.specific_force_B, sample.omega_B);
  last_imu_t_s_ = sample.t_s;
}

void GapflytMission::OnRange(const perception::RangeReading& reading) {
  if (reading.valid) odometry_.AddRange(reading.range_m);
}

void GapflytMission::OnFrame(const perception::Frame& frame) {
  if (frame.camera_id != params_.camera_id || !front_ends_) return;
  if (phase_ == GapflytPhase::kScan) {
    if (detection_tried_ || frame.t_s < scan_feed_start_t_s_) return;
    front_ends_->Process(frame);
    const auto* ts2p =
        front_ends_->Latest<perception::Ts2pOutput>(perception::Ts2pNode::kOutputSlot);
    if (!ts2p || !ts2p->fresh) return;
    detection_tried_ = true;
    const perception::Ts2pDetection& detection = *ts2p->detection;
    std::vector<Eigen::Vector2d> contour_px;
    for (const cv::Point& p : detection.contour) contour_px.emplace_back(p.x, p.y);
    if (detection.valid && ReachesBorder(contour_px)) {
      // Sec. II's reference frame shows the whole gap: from the scan's distance an opening that
      // runs into the border is wall the segmentation took for opening (it would commit at once).
      scan_statuses_.push_back("opening reaches the image border: not wholly in view");
      return;
    }
    scan_statuses_.push_back(detection.status);
    if (detection.valid) StartServo(*ts2p);
    return;
  }
  if (phase_ != GapflytPhase::kServo) return;
  front_ends_->Process(frame);
  ServoOnFrame(
      *front_ends_->Latest<perception::OpeningTrack>(perception::GapTrackerNode::kOutputSlot));
}

void GapflytMission::StartScan(double t_s) {
  ++scans_;
  detection_tried_ = false;
  std::vector<std::unique_ptr<perception::Node>> nodes;
  nodes.push_back(std::make_unique<perception::Ts2pNode>(params_.ts2p, ""));
  nodes.push_back(std::make_unique<perception::GapTrackerNode>(params_.tracker, ""));
  front_ends_ = std::make_unique<perception::FrontEndRunner>(std::move(nodes));
  // Odd scans go along scan_direction, even ones back.
  const double sign = scans_ % 2 == 1 ? 1.0 : -1.0;
  const Eigen::Vector2d d = params_.scan_direction.normalized();
  const Eigen::Vector3d v_W = sign * params_.scan_speed_mps *
                              (Eigen::AngleAxisd(heading_rad_, Eigen::Vector3d::UnitZ()) *
                               Eigen::Vector3d(0.0, d.x(), d.y()));
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const double ramp_s = params_.scan_ramp_s, cruise_s = params_.scan_cruise_s;
  const Eigen::Vector3d p0 = hold_p_W_;
  const Eigen::Vector3d p1 = p0 + 0.5 * ramp_s * v_W;  // a symmetric ramp covers half of v T
  const Eigen::Vector3d p2 = p1 + cruise_s * v_W;
  const Eigen::Vector3d p3 = p2 + 0.5 * ramp_s * v_W;
  scan_segments_ = {MotionPrimitive(p0, zero, zero, p1, v_W, zero, ramp_s),
                    MotionPrimitive(p1, v_W, zero, p2, v_W, zero, cruise_s),
                    MotionPrimitive(p2, v_W, zero, p3, zero, zero, ramp_s)};
  // The ts2p window (stack * stride frame periods) centred on the cruise.
  const double window_s = params_.ts2p.stack * params_.ts2p.stride / params_.camera_rate_hz;
  scan_feed_start_t_s_ = t_s + ramp_s + 0.5 * (cruise_s - window_s);
  EnterPhase(GapflytPhase::kScan, t_s);
}

void GapflytMission::StartServo(const perception::Ts2pOutput& detection) {
  detection_ = detection.detection;
  detection_t_s_ = detection.reference_t_s;
  detection_p_W_ = estimate().p_WB;
  desired_set_ = false;
  lost_frames_ = 0;
  recent_errors_.clear();
  EnterPhase(GapflytPhase::kServo, last_imu_t_s_);
  // The detection's frame is already past: the tracker starts on the next frame.
}

std::optional<std::vector<Eigen::Vector2d>> GapflytMission::LevelNormalized(
    const std::vector<Eigen::Vector2d>& px) const {
  std::vector<Eigen::Vector2d> normalized;
  normalized.reserve(px.size());
  for (const Eigen::Vector2d& p : px) {
    const Eigen::Vector3d ray_C = camera_->Unproject(p);
    if (!(ray_C.z() > 1e-6)) return std::nullopt;
    normalized.emplace_back(ray_C.x() / ray_C.z(), ray_C.y() / ray_C.z());
  }
  return servo::LevelView(normalized, estimate().q_WB.toRotationMatrix(), T_BC_.linear());
}

bool GapflytMission::TouchesBorder(const std::vector<Eigen::Vector2d>& contour_px) const {
  // Only a contour near the goal view's size: a far opening whose detection bled into the
  // border is not one about to fill the view.
  std::vector<cv::Point2f> points;
  for (const Eigen::Vector2d& p : contour_px) points.emplace_back(p.x(), p.y());
  const double image_area_px = static_cast<double>(camera_->width()) * camera_->height();
  if (cv::contourArea(points) < 0.5 * params_.commit_area_fraction * image_area_px) return false;
  return ReachesBorder(contour_px);
}

bool GapflytMission::ReachesBorder(const std::vector<Eigen::Vector2d>& contour_px) const {
  const double margin = params_.commit_border_px;
  // Pixel centres run from 0 to size - 1 (camera_model.h).
  const double max_u = camera_->width() - 1.0 - margin, max_v = camera_->height() - 1.0 - margin;
  for (const Eigen::Vector2d& p : contour_px) {
    if (p.x() <= margin || p.y() <= margin || p.x() >= max_u || p.y() >= max_v) return true;
  }
  return false;
}

void GapflytMission::ServoOnFrame(const perception::OpeningTrack& track) {
  const double t_s = track.t_s;
  if (!servo_timed_out_ && last_imu_t_s_ - phase_start_t_s_ > params_.max_servo_s) {
    servo_timed_out_ = true;
    char reason[80];
    std::snprintf(reason, sizeof(reason), "servo did not converge in %.1f s", params_.max_servo_s);
    reason_ = reason;
  }
  if (!track.valid || track.contour_px.size() < 3) {
    if (++lost_frames_ >= params_.max_lost_frames) {
      // Lost where the opening already filled most of the goal view: close enough to commit.
      if (CommitAllowed() && last_track_ && last_step_ &&
          TouchesBorder(last_track_->contour_px) && AimWithinReach()) {
        Commit("track lost at the border", last_imu_t_s_);
      } else {
        Abort("opening track lost", last_imu_t_s_);
      }
    }
    return;
  }
  lost_frames_ = 0;
  ++frames_tracked_;
  last_track_ = track;
  if (CommitAllowed() && TouchesBorder(track.contour_px) && AimWithinReach()) {
    Commit("opening at the image border", last_imu_t_s_);
    return;
  }
  const std::optional<std::vector<Eigen::Vector2d>> contour_n = LevelNormalized(track.contour_px);
  const std::optional<std::vector<Eigen::Vector2d>> safe_n = LevelNormalized({track.safe_point_px});
  if (!contour_n || !safe_n) return;  // tilted beyond the level view: keep the last reference
  if (!desired_set_ && servo_.law() == servo::GapServoLaw::kMoments) {
    // Goal view: this contour centred on the body axis's image, commit_area_fraction of the image.
    const Eigen::Matrix4d m = servo::PolygonMoments(*contour_n);
    const Eigen::Vector2d centroid(m(1, 0) / m(0, 0), m(0, 1) / m(0, 0));
    const Eigen::Vector3d x_B_C = T_BC_.linear().transpose() * Eigen::Vector3d::UnitX();
    const Eigen::Vector2d axis_n = x_B_C.head<2>() / x_B_C.z();
    const Eigen::Vector4d k = camera_->intrinsics();  // fx, fy, cx, cy
    const double image_area_n = (camera_->width() / k(0)) * (camera_->height() / k(1));
    const double scale = std::sqrt(params_.commit_area_fraction * image_area_n / m(0, 0));
    std::vector<Eigen::Vector2d> desired;
    for (const Eigen::Vector2d& p : *contour_n) desired.push_back(axis_n + scale * (p - centroid));
    servo_.SetDesired(desired, params_.commit_depth_m);
    desired_set_ = true;
  }
  servo::OpeningView view;
  view.t_s = t_s;
  view.contour_n = *contour_n;
  view.safe_point_n = safe_n->front();
  const servo::ServoStepResult step = servo_.Step(view);
  last_step_ = step;
  if (step.status != servo::ServoStatus::kOk) return;
  Eigen::Vector3d v_B = step.reference.v_B;
  if (v_B.norm() > params_.max_servo_speed_mps) v_B *= params_.max_servo_speed_mps / v_B.norm();
  servo_v_B_ = v_B;
  servo_trace_.push_back({t_s, step.error_norm, v_B});
  if (CommitAllowed() && servo_.law() == servo::GapServoLaw::kMoments &&
      step.error_norm < params_.commit_error && ErrorAtRest(t_s, step.error)) {
    Commit("moment servo converged", last_imu_t_s_);
  }
}

bool GapflytMission::CommitAllowed() const {
  // The blind line runs on the odometry alone: not while it coasts through suspected wind (the
  // air is then pushing the vehicle and the velocity is integrated acceleration only).
  return !servo_timed_out_ && !odometry_.coasting();
}

bool GapflytMission::ErrorAtRest(double t_s, const Eigen::VectorXd& error) {
  recent_errors_.emplace_back(t_s, error);
  while (t_s - recent_errors_.front().first > params_.commit_rate_window_s) {
    recent_errors_.pop_front();
  }
  // A window shorter than half its length (the servo just started, frames dropped): not yet.
  const double span_s = t_s - recent_errors_.front().first;
  if (span_s < 0.5 * params_.commit_rate_window_s) return false;
  const Eigen::VectorXd& oldest = recent_errors_.front().second;
  if (oldest.size() != error.size()) return false;
  return (error - oldest).norm() / span_s < params_.commit_max_error_rate;
}

std::optional<Eigen::Vector3d> GapflytMission::AimOffsetB() const {
  if (!detection_ || !last_track_) return std::nullopt;
  // Wall distance at the scan: the stacked mean flow of the wall (F mode) is f |b| / Z_F over the
  // stack's mean baseline, offsets +-stride .. +-(N/2) stride frames at the scan's speed
  // (seed 002 Sec. II: flow magnitude = inverse depth times the baseline).
  const int half_stack = params_.ts2p.stack / 2;
  const double mean_baseline_m = params_.scan_speed_mps / params_.camera_rate_hz *
                                 params_.ts2p.stride * 0.5 * (half_stack + 1);
  const double f_px = camera_->intrinsics().x();
  const double wall_at_scan_m = f_px * mean_baseline_m / detection_->foreground_flow_px;
  const Eigen::Vector3d forward_W =
      Eigen::AngleAxisd(heading_rad_, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d::UnitX();
  double wall_m = wall_at_scan_m - (estimate().p_WB - detection_p_W_).dot(forward_W);
  // The odometry's forward travel ran past the wall (a gust: the drag-aided odometry measures the
  // air-relative velocity, control/drag_aided_odometry.h) or the scan saw no wall flow: the goal
  // view's nominal depth, near which the opening fills the view.
  if (!std::isfinite(wall_m) || wall_m <= 0.0) wall_m = params_.commit_depth_m;
  // Image points on the wall, in the level body frame: from the camera's optical centre (its
  // lever arm on the body) along the level-view ray to the wall.
  const auto on_wall_B = [&](const Eigen::Vector2d& n) -> std::optional<Eigen::Vector3d> {
    const Eigen::Vector3d ray_B = T_BC_.linear() * n.homogeneous();
    if (!(ray_B.x() > 1e-6)) return std::nullopt;
    return T_BC_.translation() + ray_B * (wall_m / ray_B.x());
  };
  const std::optional<std::vector<Eigen::Vector2d>> safe_n =
      LevelNormalized({last_track_->safe_point_px});
  if (!safe_n) return std::nullopt;
  const std::optional<Eigen::Vector3d> safe_B = on_wall_B(safe_n->front());
  if (!safe_B) return std::nullopt;
  Eigen::Vector3d offset_B = *safe_B;
  // The contour on the wall in the plane's (right, down) = (-y_B, -z_B) coordinates.
  std::vector<Eigen::Vector2d> polygon;
  if (const auto contour_n = LevelNormalized(last_track_->contour_px)) {
    for (const Eigen::Vector2d& n : *contour_n) {
      if (const auto p_B = on_wall_B(n)) polygon.emplace_back(-p_B->y(), -p_B->z());
    }
  }
  // The safe point unless the vehicle fits clearly better elsewhere (a tight triangle's base):
  // the contour's shape is only as good as the tracker keeps it, the safe point is smoothed.
  const std::vector<FootprintDisk> footprint =
      LevelFootprint(vehicle_, params_.body_radius_m, params_.propeller_radius_m);
  const Eigen::Vector2d safe(-safe_B->y(), -safe_B->z());
  if (polygon.size() == last_track_->contour_px.size()) {
    const FootprintPlacement best = BestFootprintPlacement(polygon, footprint, safe);
    if (best.clearance_m > 0.0 &&
        FootprintClearance(polygon, footprint, safe) < best.clearance_m - kAimClearanceGainM) {
      offset_B = Eigen::Vector3d(0.0, -best.center.x(), -best.center.y());
    }
  }
  offset_B.x() = 0.0;  // only sideways and vertically: the line still runs along the heading
  return offset_B;
}

bool GapflytMission::AimWithinReach() const {
  const std::optional<Eigen::Vector3d> offset_B = AimOffsetB();
  return !offset_B || offset_B->norm() <= params_.commit_max_aim_offset_m;
}

void GapflytMission::Commit(const std::string& reason, double t_s) {
  reason_ = reason;
  commit_t_s_ = t_s;
  commit_aim_offset_B_ = AimOffsetB();
  Eigen::Vector3d correction_B = commit_aim_offset_B_.value_or(Eigen::Vector3d::Zero());
  if (correction_B.norm() > params_.max_aim_correction_m) {
    correction_B *= params_.max_aim_correction_m / correction_B.norm();
  }
  aim_correction_W_ = Eigen::AngleAxisd(heading_rad_, Eigen::Vector3d::UnitZ()) * correction_B;
  go_through_start_W_ = estimate().p_WB + aim_correction_W_;
  hold_p_W_ = go_through_start_W_;
  EnterPhase(GapflytPhase::kGoThrough, t_s);
}

perception::AutopilotCommand GapflytMission::Track(
    const control::TrajectoryPoint& reference) const {
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = controller_.Compute(estimate(), reference).command;
  return command;
}

perception::AutopilotCommand GapflytMission::TrackBodyVelocity(double t_s,
                                                               const Eigen::Vector3d& v_B) const {
  return Track(BodyVelocityTrajectoryPoint(t_s, estimate().p_WB, heading_rad_, v_B));
}

control::TrajectoryPoint GapflytMission::HoldReference(double t_s) const {
  control::TrajectoryPoint reference;
  reference.t_s = t_s;
  reference.p_W = hold_p_W_;
  reference.heading_rad = heading_rad_;
  return reference;
}

perception::AutopilotCommand GapflytMission::Step(double t_s) {
  for (;;) {
    std::optional<perception::AutopilotCommand> command;
    switch (phase_) {
      case GapflytPhase::kCalibrate:
        command = StepCalibrate(t_s);
        break;
      case GapflytPhase::kSettle:
        command = StepSettle(t_s);
        break;
      case GapflytPhase::kScan:
        command = StepScan(t_s);
        break;
      case GapflytPhase::kServo:
        command = StepServo(t_s);
        break;
      case GapflytPhase::kGoThrough:
        command = StepGoThrough(t_s);
        break;
      case GapflytPhase::kStop:
      case GapflytPhase::kDone:
      case GapflytPhase::kAborted:
        command = StepHold(t_s);
        break;
    }
    if (command) return *command;
  }
}

std::optional<perception::AutopilotCommand> GapflytMission::StepCalibrate(double t_s) {
  if (odometry_.started()) {
    hold_p_W_ = estimate().p_WB;
    EnterPhase(GapflytPhase::kSettle, t_s);
    return std::nullopt;
  }
  // At rest in the attitude the run started hovering in (control/gyro_attitude_hold.h): zero
  // rates would let a weak rotor tilt the vehicle while the odometry calibrates "at rest".
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = attitude_hold_.Command(vehicle_.gravity_mps2);
  return command;
}

std::optional<perception::AutopilotCommand> GapflytMission::StepSettle(double t_s) {
  if (t_s - phase_start_t_s_ >= params_.settle_s) {
    StartScan(t_s);
    return std::nullopt;
  }
  return Track(HoldReference(t_s));
}

double GapflytMission::ScanDuration() const {
  return 2.0 * params_.scan_ramp_s + params_.scan_cruise_s;
}

control::TrajectoryPoint GapflytMission::ScanReference(double t_rel) const {
  double t = std::clamp(t_rel, 0.0, ScanDuration());
  for (std::size_t i = 0; i < scan_segments_.size(); ++i) {
    if (t <= scan_segments_[i].duration_s() || i + 1 == scan_segments_.size()) {
      return scan_segments_[i].Sample(std::min(t, scan_segments_[i].duration_s()));
    }
    t -= scan_segments_[i].duration_s();
  }
  return {};
}

std::optional<perception::AutopilotCommand> GapflytMission::StepScan(double t_s) {
  const double t_rel = t_s - phase_start_t_s_;
  if (t_rel >= ScanDuration()) {
    hold_p_W_ = scan_segments_.back().Position(scan_segments_.back().duration_s());
    if (scans_ >= params_.max_scans) {
      Abort("no opening detected in " + std::to_string(scans_) + " scans", t_s);
      return std::nullopt;
    }
    StartScan(t_s);
    return std::nullopt;
  }
  control::TrajectoryPoint reference = ScanReference(t_rel);
  reference.t_s = t_s;
  reference.heading_rad = heading_rad_;
  return Track(reference);
}

std::optional<perception::AutopilotCommand> GapflytMission::StepServo(double t_s) {
  if (std::isnan(last_servo_step_t_s_)) {
    // Start from the velocity the scan left the vehicle with (in the heading frame).
    reference_v_B_ = Eigen::AngleAxisd(-heading_rad_, Eigen::Vector3d::UnitZ()) * estimate().v_W;
  } else {
    // Forward only: lateral and vertical follow the servo at once (a lag there overshoots).
    const double max_change = params_.max_servo_accel_mps2 * (t_s - last_servo_step_t_s_);
    reference_v_B_.x() += std::clamp(servo_v_B_.x() - reference_v_B_.x(), -max_change, max_change);
    reference_v_B_.tail<2>() = servo_v_B_.tail<2>();
  }
  last_servo_step_t_s_ = t_s;
  return TrackBodyVelocity(t_s, reference_v_B_);
}

std::optional<perception::AutopilotCommand> GapflytMission::StepGoThrough(double t_s) {
  const Eigen::Vector3d p_W = estimate().p_WB;
  const Eigen::Vector3d forward_W =
      Eigen::AngleAxisd(heading_rad_, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d::UnitX();
  if ((p_W - go_through_start_W_).dot(forward_W) >= params_.go_through_distance_m) {
    hold_p_W_ = p_W;
    EnterPhase(GapflytPhase::kStop, t_s);
    return std::nullopt;
  }
  // Straight ahead at the commit's height, drifting sideways neither (the commit's lateral
  // position is the servo's last alignment).
  const Eigen::Vector3d along_W =
      go_through_start_W_ + (p_W - go_through_start_W_).dot(forward_W) * forward_W;
  control::TrajectoryPoint reference = HoldReference(t_s);
  reference.p_W = along_W;
  reference.v_W = params_.go_through_speed_mps * forward_W;
  return Track(reference);
}

perception::AutopilotCommand GapflytMission::StepHold(double t_s) {
  if (phase_ == GapflytPhase::kStop && t_s - phase_start_t_s_ >= params_.stop_hold_s) {
    EnterPhase(GapflytPhase::kDone, t_s);
  }
  perception::AutopilotCommand command = Track(HoldReference(t_s));
  command.done = phase_ == GapflytPhase::kDone;
  return command;
}

std::string GapflytMission::status() const {
  char buffer[160];
  switch (phase_) {
    case GapflytPhase::kScan:
      std::snprintf(buffer, sizeof(buffer), "scan %d/%d", scans_, params_.max_scans);
      return buffer;
    case GapflytPhase::kServo:
      std::snprintf(buffer, sizeof(buffer), "servo (%s) |e| %.3f", servo::ToString(law()),
                    last_step_ ? last_step_->error_norm : 0.0);
      return servo_timed_out_ ? buffer + std::string(", holding: ") + reason_ : buffer;
    case GapflytPhase::kGoThrough:
      return "go_through (" + reason_ + ")";
    case GapflytPhase::kAborted:
      return "aborted: " + reason_;
    default:
      return ToString(phase_);
  }
}

void GapflytMission::DrawOverlay(cv::Mat& bgr) const {
  if (front_ends_ && (phase_ == GapflytPhase::kScan || phase_ == GapflytPhase::kServo)) {
    front_ends_->DrawOverlays(bgr);
  }
  if (last_track_ && phase_ == GapflytPhase::kServo && last_track_->foe_px.allFinite()) {
    cv::drawMarker(bgr, ToPoint(last_track_->foe_px), cv::Scalar(255, 0, 255), cv::MARKER_DIAMOND,
                   14, 2);  // FOE (magenta)
  }
  // Where the body's x axis pierces the image: what x_s is servoed to (white).
  Eigen::Vector2d axis_px;
  if (camera_->Project(T_BC_.inverse().linear() * Eigen::Vector3d::UnitX(), &axis_px)) {
    cv::drawMarker(bgr, ToPoint(axis_px), cv::Scalar(255, 255, 255), cv::MARKER_CROSS, 20, 1);
  }
  std::string line = std::string("gapflyt: ") + status();
  cv::putText(bgr, line, cv::Point(8, bgr.rows - 10), cv::FONT_HERSHEY_SIMPLEX, 0.5,
              cv::Scalar(0, 255, 255), 1, cv::LINE_AA);
}

}  // namespace aperture::planning
