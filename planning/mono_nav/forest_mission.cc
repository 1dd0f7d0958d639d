#include "planning/mono_nav/forest_mission.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "perception/cpu_time.h"
#include "perception/mono_depth/mono_depth_node.h"

namespace aperture::planning {
namespace {

using perception::ThreadCpuSeconds;  // the per-module cost on one core

std::vector<std::unique_ptr<perception::Node>> MonoDepthFrontEnd(perception::MonoDepthModel model) {
  std::vector<std::unique_ptr<perception::Node>> nodes;
  nodes.push_back(std::make_unique<perception::MonoDepthNode>(
      std::move(model), "", std::vector<std::filesystem::path>{}));
  return nodes;
}

// Each component of a clamped into [-limit, limit].
Eigen::Vector3d ClampComponents(const Eigen::Vector3d& a, const Eigen::Vector3d& limit) {
  return a.cwiseMax(-limit).cwiseMin(limit);
}

// Zeroes (BackProjectGrid then leaves out) the patches of d_eff_m whose metric point, at the
// estimated depth D_E along the patch centre's ray, lies less than clearance_m above the ground
// plane z_W = ground_height_m: the ground is not an obstacle to a vehicle flying above it, but
// the EDT's compression of depth along the rays lifts it to the vehicle's height (a ground patch
// at depth D, h below the camera, lands h d_eff / D below it), where it blocks every path.
void MaskGround(const cv::Mat& depth_m, const Eigen::Vector2d& patch_px,
                const perception::CameraModel& camera, const Eigen::Isometry3d& T_WC,
                double ground_height_m, double clearance_m, cv::Mat* d_eff_m) {
  for (int r = 0; r < depth_m.rows; ++r) {
    for (int c = 0; c < depth_m.cols; ++c) {
      // Patch centre as BackProjectGrid takes it (pixel centres at integers).
      const Eigen::Vector2d px((c + 0.5) * patch_px.x() - 0.5, (r + 0.5) * patch_px.y() - 0.5);
      const Eigen::Vector3d bearing_C = camera.Unproject(px);
      if (!(bearing_C.z() > 1e-6)) continue;
      const Eigen::Vector3d p_W = T_WC * (bearing_C * (depth_m.at<float>(r, c) / bearing_C.z()));
      if (p_W.z() < ground_height_m + clearance_m) d_eff_m->at<float>(r, c) = 0.0f;
    }
  }
}

// The selector's parameters with max_bearing_rad no wider than the camera's horizontal field of
// view: the smaller bearing in B of the rays through the image's left and right edge centres.
WaypointSelectorParams WithCameraFieldOfView(WaypointSelectorParams params,
                                             const perception::CameraModel* camera,
                                             const Eigen::Isometry3d& T_BC) {
  if (camera == nullptr) return params;  // the constructor rejects it
  const double row = 0.5 * (camera->height() - 1);
  for (const double column : {0.0, camera->width() - 1.0}) {
    const Eigen::Vector3d ray_B = T_BC.linear() * camera->Unproject(Eigen::Vector2d(column, row));
    params.max_bearing_rad =
        std::min(params.max_bearing_rad, std::atan2(std::abs(ray_B.y()), ray_B.x()));
  }
  return params;
}

// The frames for which `counted` holds.
int CountForestFrames(const std::vector<ForestFrameRecord>& frames,
                      bool (*counted)(const ForestFrameRecord&)) {
  return static_cast<int>(std::count_if(frames.begin(), frames.end(), counted));
}

}  // namespace

std::optional<double> ForestHeadingTarget(const Eigen::Vector3d& p_W, const Eigen::Vector3d& goal_W,
                                          const Eigen::Vector3d& v_reference_W,
                                          double travel_min_speed_mps,
                                          double max_travel_off_heading_rad,
                                          std::optional<double> look_aside_rad, bool backing_off,
                                          double hold_within_m) {
  const Eigen::Vector2d to_goal = (goal_W - p_W).head<2>();
  if (backing_off || to_goal.norm() <= hold_within_m) return std::nullopt;
  const double goal_rad = std::atan2(to_goal.y(), to_goal.x());
  const Eigen::Vector2d v = v_reference_W.head<2>();
  if (v.norm() > travel_min_speed_mps) {
    const double travel_rad = std::atan2(v.y(), v.x());
    const double off_rad = std::clamp(std::remainder(goal_rad - travel_rad, 2.0 * M_PI),
                                      -max_travel_off_heading_rad, max_travel_off_heading_rad);
    return std::remainder(travel_rad + off_rad, 2.0 * M_PI);
  }
  if (look_aside_rad) return look_aside_rad;
  return goal_rad;
}

bool GoalLeftTheView(const Eigen::Vector3d& p_W, const Eigen::Vector3d& goal_W,
                     const Eigen::Vector3d& v_reference_W, double travel_min_speed_mps,
                     double max_travel_off_heading_rad, double max_bearing_rad) {
  const Eigen::Vector2d to_goal = (goal_W - p_W).head<2>();
  const Eigen::Vector2d v = v_reference_W.head<2>();
  if (!(v.norm() > travel_min_speed_mps) || to_goal.norm() <= kHeadingHoldWithinM) return false;
  const double goal_off_travel_rad = std::abs(std::remainder(
      std::atan2(to_goal.y(), to_goal.x()) - std::atan2(v.y(), v.x()), 2.0 * M_PI));
  return goal_off_travel_rad > max_travel_off_heading_rad + max_bearing_rad;
}

void ForestMissionParams::Validate() const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("ForestMissionParams: " + what);
  };
  require(goal_W.allFinite(), "goal_W must be finite");
  require(spline_path_points >= 6,
          "spline_path_points must be >= 6 (a quintic B-spline needs 6 control points)");
  require(replan_from_estimate_m > 0.0, "replan_from_estimate_m must be > 0");
  require(extension_m >= 0.0, "extension_m must be >= 0");
  require(extension_standoff_m >= 0.0, "extension_standoff_m must be >= 0");
  require(max_yaw_rate_radps >= 0.0, "max_yaw_rate_radps must be >= 0 (0: fixed heading)");
  require(travel_heading_min_speed_mps > 0.0, "travel_heading_min_speed_mps must be > 0");
  require(max_travel_off_heading_rad >= 0.0 && max_travel_off_heading_rad <= M_PI,
          "max_travel_off_heading_rad must be in [0, pi] (pi: the goal's bearing in flight too)");
  require(recovery_after_s > 0.0, "recovery_after_s must be > 0 (inf: no recovery)");
  require(rest_speed_mps > 0.0, "rest_speed_mps must be > 0");
  require(recovery_min_backoff_m > kMinSplineIntervalM * (spline_path_points - 1),
          "recovery_min_backoff_m must be > 0.05 m x (spline_path_points - 1), the shortest "
          "spline planned");
  require(recovery_backoff_m >= recovery_min_backoff_m,
          "recovery_backoff_m must be >= recovery_min_backoff_m");
  require(recovery_look_aside_rad > 0.0 && recovery_look_aside_rad < M_PI,
          "recovery_look_aside_rad must be in (0, pi)");
  require(direct_goal_distance_m >= 0.0, "direct_goal_distance_m must be >= 0");
  require(goal_reached_m > 0.0, "goal_reached_m must be > 0");
  require(goal_speed_mps > 0.0, "goal_speed_mps must be > 0");
  require(camera_id >= 0, "camera_id must be >= 0");
  require(std::isfinite(ground_height_m), "ground_height_m must be finite");
  require(ground_clearance_m >= 0.0, "ground_clearance_m must be >= 0");
  edt.Validate();
  waypoints.Validate();
  limits.Validate();
  spline.Validate();
  fusion.Validate();
}

ForestMission::ForestMission(const ForestMissionParams& params,
                             std::shared_ptr<const perception::CameraModel> camera,
                             const Eigen::Isometry3d& T_BC,
                             const control::VehicleParameters& vehicle,
                             perception::MonoDepthModel model)
    : params_((params.Validate(), params)),
      camera_(std::move(camera)),
      T_BC_(T_BC),
      vehicle_(vehicle),
      front_ends_(MonoDepthFrontEnd(std::move(model))),
      selector_(WithCameraFieldOfView(params.waypoints, camera_.get(), T_BC)),
      controller_(vehicle, params.controller),
      fusion_(params.fusion) {
  if (!camera_) throw std::invalid_argument("ForestMission: camera is null; pass the camera model");
  perception::RequireRigid(T_BC_, "ForestMission T_BC");
}

void ForestMission::OnImu(const perception::ImuSample& sample) { fusion_.AddImu(sample); }

void ForestMission::OnOdometry(const perception::PoseMeasurement& pose_WB) {
  fusion_.AddPose(pose_WB);
}

std::optional<control::QuadState> ForestMission::estimate() const {
  const std::optional<perception::PoseImuEstimate> e = fusion_.estimate();
  if (!e) return std::nullopt;
  return e->state;
}

int ForestMission::replans() const {
  int sum = 0;
  for (const ForestFrameRecord& record : frames_) sum += record.replans;
  return sum;
}

int ForestMission::selections() const {
  return CountForestFrames(frames_, [](const ForestFrameRecord& r) { return r.selected; });
}

int ForestMission::frames_replanned() const {
  return CountForestFrames(frames_, [](const ForestFrameRecord& r) { return r.replans > 0; });
}

int ForestMission::back_offs() const {
  return CountForestFrames(frames_, [](const ForestFrameRecord& r) { return r.backed_off; });
}

int ForestMission::look_asides() const {
  return CountForestFrames(frames_, [](const ForestFrameRecord& r) { return r.looked_aside; });
}

int ForestMission::turns_to_goal() const {
  return CountForestFrames(frames_, [](const ForestFrameRecord& r) { return r.turned_to_goal; });
}

int ForestMission::frames_without_path() const {
  return CountForestFrames(frames_, [](const ForestFrameRecord& r) { return !r.planned; });
}

control::TrajectoryPoint ForestMission::Reference(double t_s) const {
  control::TrajectoryPoint reference = *hold_;
  if (spline_) {
    const double t =
        std::clamp(t_s - spline_start_t_s_, spline_->StartParameter(), spline_->EndParameter());
    reference.p_W = spline_->Evaluate(t, 0);
    reference.v_W = spline_->Evaluate(t, 1);
    reference.a_W = spline_->Evaluate(t, 2);
    reference.j_W = spline_->Evaluate(t, 3);
    reference.s_W = spline_->Evaluate(t, 4);
    if (t >= spline_->EndParameter())
      reference.v_W = reference.a_W = reference.j_W = reference.s_W = Eigen::Vector3d::Zero();
  }
  reference.t_s = t_s;
  reference.heading_rad = heading_rad_;
  reference.heading_rate_radps = heading_rate_radps_;
  return reference;
}

void ForestMission::TurnHeading(std::optional<double> target_rad, double dt_s) {
  heading_rate_radps_ = 0.0;
  heading_error_rad_ = 0.0;
  if (!target_rad || !(dt_s > 0.0)) return;
  const double error = std::remainder(*target_rad - heading_rad_, 2.0 * M_PI);
  const double max_step = params_.max_yaw_rate_radps * dt_s;
  const double step = std::clamp(error, -max_step, max_step);
  heading_rad_ = std::remainder(heading_rad_ + step, 2.0 * M_PI);
  heading_rate_radps_ = step / dt_s;
  heading_error_rad_ = error - step;
}

bool ForestMission::AtRest(double t_s, const control::QuadState& x) const {
  const bool flown_out = !spline_ || t_s - spline_start_t_s_ >= spline_->EndParameter();
  return flown_out && x.v_W.norm() <= params_.rest_speed_mps &&
         std::abs(heading_error_rad_) <= kHeadingSettledRad;
}

void ForestMission::Recover(double t_s, const control::QuadState& x, ForestFrameRecord* record) {
  if (!(t_s - still_since_t_s_ >= params_.recovery_after_s) || !AtRest(t_s, x)) return;
  still_since_t_s_ = t_s;
  // Back off along the flown path, latest point first.
  const std::vector<Eigen::Vector3d> path_W =
      trail_.BackOffPath(x.p_WB, params_.recovery_backoff_m);
  if (PolylineLength(path_W) >= params_.recovery_min_backoff_m && FollowPath(t_s, x, path_W)) {
    trail_.Retrace(path_W);
    backing_off_ = true;
    look_aside_rad_.reset();
    record->backed_off = true;
    return;
  }
  // No flown path behind: turn the camera to one side of the goal, the other side next time.
  const Eigen::Vector2d to_goal = (params_.goal_W - x.p_WB).head<2>();
  look_aside_side_ = -look_aside_side_;
  look_aside_rad_ = std::remainder(
      std::atan2(to_goal.y(), to_goal.x()) + look_aside_side_ * params_.recovery_look_aside_rad,
      2.0 * M_PI);
  record->looked_aside = true;
}

bool ForestMission::TurnToGoal(double t_s, const control::QuadState& x,
                               ForestFrameRecord* record) {
  const control::TrajectoryPoint reference = Reference(t_s);
  if (turning_to_goal_) {
    const bool flown_out = !spline_ || t_s - spline_start_t_s_ >= spline_->EndParameter();
    turning_to_goal_ = !flown_out || std::abs(heading_error_rad_) > kHeadingSettledRad;
    return turning_to_goal_;
  }
  // Now and kTravelLookAheadS on: a spline planned from a back-off's backward velocity reverses
  // within ~0.3 s, its travel only briefly points away from the goal.
  const auto left_the_view = [&](const Eigen::Vector3d& v_reference_W) {
    return GoalLeftTheView(x.p_WB, params_.goal_W, v_reference_W,
                           params_.travel_heading_min_speed_mps,
                           params_.max_travel_off_heading_rad, selector_.params().max_bearing_rad);
  };
  if (backing_off_ || !left_the_view(reference.v_W) ||
      !left_the_view(Reference(t_s + kTravelLookAheadS).v_W)) {
    return false;
  }
  const Eigen::Vector2d v = reference.v_W.head<2>();
  // Stop straight ahead, over the distance of 1 s at the current speed (2 s, 4 s when the spline
  // solver does not converge on it) and no less than the shortest spline.
  bool stopping = false;
  for (const double travel_s : {1.0, 2.0, 4.0}) {
    const double stop_m = std::max(v.norm() * travel_s,
                                   kMinSplineIntervalM * (params_.spline_path_points - 1) * 1.2);
    Eigen::Vector3d stop_W = reference.p_W;
    stop_W.head<2>() += v.normalized() * stop_m;
    if ((stopping = FollowPath(t_s, x, {reference.p_W, stop_W}))) break;
  }
  if (!stopping) return false;
  turning_to_goal_ = true;
  look_aside_rad_.reset();
  record->turned_to_goal = true;
  return true;
}

void ForestMission::OnFrame(const perception::Frame& frame) {
  if (frame.camera_id != params_.camera_id || !hold_ || goal_reached_) return;
  ForestFrameRecord record;
  record.t_s = frame.t_s;
  const double t0 = ThreadCpuSeconds();
  front_ends_.Process(frame);
  record.perception_s = ThreadCpuSeconds() - t0;
  const auto* depth =
      front_ends_.Latest<perception::MonoDepthEstimate>(perception::MonoDepthNode::kOutputSlot);
  if (depth == nullptr) return;
  const double t1 = ThreadCpuSeconds();
  const double t_s = estimate()->t_s;
  if (TurnToGoal(t_s, *estimate(), &record)) {
    record.planning_s = ThreadCpuSeconds() - t1;
    frames_.push_back(record);
    return;
  }
  Plan(t_s, *depth, &record);
  if (record.planned) {
    still_since_t_s_ = t_s;
    backing_off_ = false;
  } else {
    Recover(t_s, *estimate(), &record);
  }
  record.planning_s = ThreadCpuSeconds() - t1;
  frames_.push_back(record);
}

void ForestMission::Plan(double t_s, const perception::MonoDepthEstimate& depth,
                         ForestFrameRecord* record) {
  const control::QuadState x = *estimate();
  const Eigen::Matrix3d R_WB = x.q_WB.toRotationMatrix();
  last_T_WB_.linear() = R_WB;
  last_T_WB_.translation() = x.p_WB;

  // Sec. III-B: d_eff = EDT{d_obs}, d_obs = D_E - avg(e_ln); Table IV's baseline: d_eff = d_obs.
  cv::Mat d_obs_m = depth.depth_m - params_.edt.depth_error_margin_m;
  MaskGround(depth.depth_m, depth.grid.frame_patch_px, *camera_, last_T_WB_ * T_BC_,
             params_.ground_height_m, params_.ground_clearance_m, &d_obs_m);
  cv::Mat d_eff_m = d_obs_m;
  if (params_.ego_dynamic) {
    d_eff_m = EgoDynamicTransform(depth.depth_m, params_.edt);
    d_eff_m.setTo(0.0f, d_obs_m <= 0.0f);  // the ground mask
  }
  // Selection in the heading frame H (B's origin, z up, x along B's estimated heading): the
  // waypoint height is then a height (max_height_from_goal_m) whatever the vehicle's tilt, and
  // the field of view (seen space) is the camera's whatever the heading reference.
  const Eigen::Matrix3d R_WH =
      Eigen::AngleAxisd(std::atan2(R_WB(1, 0), R_WB(0, 0)), Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Matrix3d R_HB = R_WH.transpose() * R_WB;
  const auto to_H = [&](std::vector<Eigen::Vector3d> points_B) {
    for (Eigen::Vector3d& p : points_B) p = R_HB * p;
    return points_B;
  };
  std::vector<Eigen::Vector3d> points_H =
      to_H(BackProjectGrid(d_eff_m, depth.grid.frame_patch_px, *camera_, T_BC_));
  // Metric obstacles (d_obs) for the spatial windows: the path is flown in metric space.
  const std::vector<Eigen::Vector3d> obstacles_H =
      to_H(BackProjectGrid(d_obs_m, depth.grid.frame_patch_px, *camera_, T_BC_));
  const Eigen::Vector3d goal_H = R_WH.transpose() * (params_.goal_W - x.p_WB);
  const Eigen::Vector3d v_H = R_WH.transpose() * x.v_W;
  const auto to_W = [&](const std::vector<Eigen::Vector3d>& path_H) {
    std::vector<Eigen::Vector3d> path_W;
    for (const Eigen::Vector3d& p : path_H) path_W.push_back(x.p_WB + R_WH * p);
    return path_W;
  };

  // Near the goal: straight to it when its spatial windows are free.
  if (goal_H.norm() <= params_.direct_goal_distance_m) {
    std::vector<Eigen::Vector3d> path_H;
    const int samples = selector_.params().path_samples;
    for (int k = 0; k <= samples; ++k) path_H.push_back(goal_H * (double(k) / samples));
    if (selector_.PathIsFree(path_H, obstacles_H)) {
      record->direct = true;
      record->planned = FollowPath(t_s, x, to_W(path_H));
      return;
    }
  }
  // Sec. III-C, III-D: the optimal (or random) segment whose Bezier path is free.
  const WaypointSelection selection = selector_.Select(
      std::move(points_H), v_H, goal_H, params_.waypoint_order,
      params_.random_seed + static_cast<std::uint64_t>(frames_.size()), &obstacles_H);
  record->selected = true;
  record->segments = static_cast<int>(selection.segments.size());
  record->replans = selection.Replans();
  if (!selection.chosen) return;
  std::vector<Eigen::Vector3d> path_H = selection.path_B;
  selector_.ExtendTowardsGoal(goal_H, obstacles_H, params_.extension_m,
                              params_.extension_standoff_m, &path_H);
  record->planned = FollowPath(t_s, x, to_W(path_H));
}

bool ForestMission::FollowPath(double t_s, const control::QuadState& x,
                               const std::vector<Eigen::Vector3d>& path_W) {
  // Start state: the current reference, unless the vehicle is far from it (Sec. III-F replans
  // the whole trajectory at every update; starting from the reference keeps the command smooth).
  control::TrajectoryPoint start = Reference(t_s);
  if ((start.p_W - x.p_WB).norm() > params_.replan_from_estimate_m) {
    start.p_W = x.p_WB;
    start.v_W = x.v_W;
    start.a_W.setZero();
  }
  // The end speed must not exceed v_max and the start acceleration a_max (PlanMinTimeBSpline).
  const double speed = start.v_W.norm();
  const double max_speed = params_.limits.max_speed_mps * 0.999;
  if (speed > max_speed) start.v_W *= max_speed / speed;
  start.a_W = ClampComponents(start.a_W, 0.999 * params_.limits.max_acceleration_mps2);

  // The path from the start, resampled to spline_path_points points evenly spaced in arc length
  // (chord-length interpolation of unevenly spaced points makes the quintic oscillate).
  std::vector<Eigen::Vector3d> polyline{start.p_W};
  polyline.insert(polyline.end(), path_W.begin() + 1, path_W.end());
  std::vector<double> arc{0.0};
  for (size_t k = 1; k < polyline.size(); ++k) {
    arc.push_back(arc.back() + (polyline[k] - polyline[k - 1]).norm());
  }
  const int n = params_.spline_path_points - 1;
  if (!(arc.back() > kMinSplineIntervalM * n)) return false;  // too short to be worth a spline
  std::vector<Eigen::Vector3d> points_W{start.p_W};
  size_t segment = 1;
  for (int k = 1; k <= n; ++k) {
    const double s = arc.back() * k / n;
    while (segment + 1 < arc.size() && arc[segment] < s) ++segment;
    const double span = arc[segment] - arc[segment - 1];
    const double f = span > 0.0 ? std::clamp((s - arc[segment - 1]) / span, 0.0, 1.0) : 1.0;
    points_W.push_back(polyline[segment - 1] + f * (polyline[segment] - polyline[segment - 1]));
  }
  MinTimeBSplineResult result;
  try {
    result = PlanMinTimeBSpline(points_W, start.v_W, start.a_W, Eigen::Vector3d::Zero(),
                                Eigen::Vector3d::Zero(), params_.limits, params_.spline);
  } catch (const std::invalid_argument&) {
    return false;  // degenerate path (points too close): keep the current spline
  }
  if (!result.ok()) return false;
  spline_ = std::move(result.trajectory);
  spline_start_t_s_ = t_s;
  last_path_W_ = path_W;
  return true;
}

perception::AutopilotCommand ForestMission::Step(double t_s) {
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  const std::optional<control::QuadState> x = estimate();
  if (!x) {  // no odometry yet: level, hover thrust (the SITL starts hovering)
    command.thrust_rates.collective_thrust_mps2 = vehicle_.gravity_mps2;
    return command;
  }
  if (!hold_) {
    const Eigen::Matrix3d R_WB = x->q_WB.toRotationMatrix();
    heading_rad_ = std::atan2(R_WB(1, 0), R_WB(0, 0));
    control::TrajectoryPoint hold;
    hold.p_W = x->p_WB;
    hold_ = hold;
    last_step_t_s_ = t_s;
    still_since_t_s_ = t_s;
  }
  if (!goal_reached_) {
    const control::TrajectoryPoint before = Reference(t_s);
    if (before.v_W.head<2>().norm() > params_.travel_heading_min_speed_mps) look_aside_rad_.reset();
    TurnHeading(ForestHeadingTarget(
                    x->p_WB, params_.goal_W, before.v_W, params_.travel_heading_min_speed_mps,
                    params_.max_travel_off_heading_rad, look_aside_rad_, backing_off_),
                t_s - last_step_t_s_);
    if (backing_off_ && t_s - spline_start_t_s_ >= spline_->EndParameter()) backing_off_ = false;
    if (!backing_off_) trail_.Add(x->p_WB);
    if (!AtRest(t_s, *x)) still_since_t_s_ = t_s;
  }
  last_step_t_s_ = t_s;
  if ((params_.goal_W - x->p_WB).norm() <= params_.goal_reached_m &&
      x->v_W.norm() <= params_.goal_speed_mps) {
    goal_reached_ = true;
  }
  control::TrajectoryPoint reference = Reference(t_s);
  if (goal_reached_) {
    reference = *hold_;
    reference.p_W = params_.goal_W;
    reference.t_s = t_s;
    reference.heading_rad = heading_rad_;
  }
  command.thrust_rates = controller_.Compute(*x, reference).command;
  command.done = goal_reached_;
  return command;
}

std::string ForestMission::status() const {
  const std::optional<control::QuadState> x = estimate();
  if (!x) return "waiting for odometry";
  char line[120];
  std::snprintf(line, sizeof(line), "%s, %.1f m to the goal, %d frames, %d replans",
                goal_reached_ ? "at the goal" : "flying", (params_.goal_W - x->p_WB).norm(),
                static_cast<int>(frames_.size()), replans());
  return line;
}

void ForestMission::DrawOverlay(cv::Mat& bgr) const {
  front_ends_.DrawOverlays(bgr);
  const Eigen::Isometry3d T_CW = (last_T_WB_ * T_BC_).inverse();
  std::vector<cv::Point> pixels;
  for (const Eigen::Vector3d& p_W : last_path_W_) {
    Eigen::Vector2d px;
    if (camera_->Project(T_CW * p_W, &px)) pixels.emplace_back(int(px.x()), int(px.y()));
  }
  if (pixels.size() >= 2) {
    cv::polylines(bgr, pixels, false, cv::Scalar(0, 255, 0), 2, cv::LINE_AA);
    cv::circle(bgr, pixels.back(), 6, cv::Scalar(0, 255, 255), 2, cv::LINE_AA);
  }
}

}  // namespace aperture::planning
