#pragma once
// Forest navigation of seed 003 (Bipin et al. 2015, Fig. 2) as a perception::Autopilot flown from
// the forward colour camera, the IMU and the vehicle's odometry source:
//
//   frame --FrontEndRunner{mono_depth}--> D_E per patch (Sec. III-A)
//         --EgoDynamicTransform--> d_eff (Sec. III-B; without EDT: d_obs = D_E - margin, Table IV)
//         --ground patches left out (beyond the paper: the EDT lifts the ground into the path)
//         --BackProjectGrid + WaypointSelector--> waypoint + Bezier path (Sec. III-C, III-D), in
//           the heading frame H (z up, waypoint at the goal's height); the spatial windows check
//           the metric points d_obs, not the EDT points (EDT compresses gaps, not the vehicle);
//           the path continues towards the goal while the windows stay free (extension_m)
//         --PlanMinTimeBSpline--> quintic B-spline in W under v/a/j limits (Sec. III-E)
//   Step: the spline sampled at t, tracked by control::PositionController (flatness + attitude
//         loop, thrust + body rates) on the PoseFusion estimate.
//
// Replanning (Sec. III-F): every frame plans the whole trajectory again from the reference state
// of the current one (from the estimate when the vehicle is more than replan_from_estimate_m off
// it). Every spline ends at rest at its waypoint, so when a frame finds no traversable segment
// the vehicle keeps the previous spline and stops at a waypoint that was free. Within
// direct_goal_distance_m of the goal the straight path to it is flown when its spatial windows
// are free.
//
// Beyond the paper (each forced by a failed flight, docs/results/mononav.md):
//   * paths run only through seen space (WaypointSelectorParams::max_bearing_rad, set from the
//     camera's horizontal field of view): a window beside the field of view holds no point only
//     because nothing there was seen (layout 4 flew into a trunk 59 deg off its heading);
//   * the heading turns at up to max_yaw_rate_radps (the paper keeps psi = 0) towards the
//     direction of travel, and towards the goal at rest: with seen-space paths, a goal beside the
//     field of view could not be approached otherwise, and a heading turned towards the goal
//     while a spline planned earlier flew elsewhere took the camera off the way (layout 21);
//   * a look-ahead cut by an obstacle ends extension_standoff_m before it, so the vehicle does
//     not come to rest facing a trunk at ~1 m, too near for any path around it to pass its
//     windows (layouts 1 and 4 stalled there for 20-40 s);
//   * a recovery when the vehicle stalls (recovery_after_s at rest without a new spline): back
//     off along the flown path (FlownTrail), or at the start look aside (layouts 13, 20, 25, 35
//     stalled in front of trunks the depth model put too close);
//   * when the goal has left what the heading rule can show (GoalLeftTheView), a stop and a turn
//     to face it before planning again (the one-trunk stall course, flown with the flight
//     controller's torque observer, passed the trunk wide and sailed on past its goal).
//
// State: the odometry source's body poses (OnOdometry: a VIO or the paper's optical-flow EKF on
// hardware; in SITL a simulated one, experiments/missions/forest_flight.h) fused with the IMU by
// perception::PoseFusion. The mission never sees ground truth.
//
// Frames: W world (z up), B body (x forward), C camera (OpenCV), T_BC the camera mount. SI units;
// times on the sensor clock.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "control/position_controller.h"
#include "control/quad_state.h"
#include "control/trajectory_point.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"
#include "perception/camera/camera_model.h"
#include "perception/estimation/pose_fusion.h"
#include "perception/graph/front_end_runner.h"
#include "perception/mono_depth/mono_depth_estimator.h"
#include "perception/mono_depth/mono_depth_model.h"
#include "planning/mono_nav/bspline.h"
#include "planning/mono_nav/ego_dynamic_space.h"
#include "planning/mono_nav/flown_trail.h"
#include "planning/mono_nav/min_time_bspline.h"
#include "planning/mono_nav/waypoint_selector.h"

namespace aperture::planning {

struct ForestMissionParams {
  Eigen::Vector3d goal_W = Eigen::Vector3d::Zero();  // where to fly [m]; the flight sets it
  // false: the Table IV baseline without the ego-dynamic transform (d_eff = D_E - margin).
  bool ego_dynamic = true;
  // kRandom: Table II's baseline (segments tried in a random order, seeded per frame).
  WaypointOrder waypoint_order = WaypointOrder::kOptimal;
  std::uint64_t random_seed = 0;
  EgoDynamicParams edt;
  // The waypoint is at the goal's height (trunks are vertical: climbing does not pass them; the
  // sky's far patches would otherwise pull every waypoint up).
  WaypointSelectorParams waypoints = [] {
    WaypointSelectorParams p;
    p.max_height_from_goal_m = 0.0;
    return p;
  }();
  // 2 m/s and 2 m/s^2 (tilt under ~12 deg); the per-axis jerk bound is Sec. III-E d)'s
  // f_min omega_max / sqrt(3) = 20.8 m/s^3 with f_min = 6 m/s^2 (0.6 g, the thrust at the
  // deepest braking) and omega_max = 6 rad/s (well inside the body-rate loop's range).
  DynamicLimits limits = [] {
    DynamicLimits limits;
    limits.max_speed_mps = 2.0;
    limits.max_acceleration_mps2 = Eigen::Vector3d::Constant(2.0);
    limits.max_jerk_mps3 = Eigen::Vector3d::Constant(DynamicLimits::JerkBound(6.0, 6.0));
    return limits;
  }();
  MinTimeBSplineParams spline;
  control::PositionControllerParams controller;
  perception::PoseFusionParams fusion;  // set the IMU noise of the vehicle's IMU
  int camera_id = 0;                    // Frame::camera_id of the forward colour camera
  // The ground plane z_W [m] of the odometry frame (a range sensor measures it on hardware), and
  // the height above it below which a depth patch counts as ground, not obstacle [m]: 0.3 m is
  // above the label widths' depth error at the horizon and below the flight height of 1.5 m.
  double ground_height_m = 0.0;
  double ground_clearance_m = 0.3;
  // Points, evenly spaced along the path, that the spline interpolates (>= 6, a quintic's
  // control points; few points keep the time-optimal spline from being jerk-bound on wiggles).
  int spline_path_points = 6;
  // The vehicle is this far from the current spline's reference -> replan from the estimate [m].
  double replan_from_estimate_m = 0.5;
  // Beyond the paper: the path continues from the waypoint towards the goal for up to this
  // length [m], as far as the spatial windows on the metric obstacles stay free. The waypoint
  // (pulled back before its segment in EDT space) is 1-4 m ahead, and a spline that stops there
  // never gets the vehicle to speed; the extension is checked like the path, so the spline still
  // ends at rest where the map was free.
  double extension_m = 4.0;
  // A look-ahead cut by an obstacle's window ends this far before the blocked sample [m]: at
  // rest ~1 m from a trunk, the trunk's window blocks every path around it; from ~2 m the
  // Bezier paths beside it pass.
  double extension_standoff_m = 1.5;
  // Within this distance of the goal, fly straight to it when that path is free [m].
  double direct_goal_distance_m = 4.0;
  // Done (AutopilotCommand::done) within this distance of the goal and below goal_speed_mps.
  double goal_reached_m = 0.3;
  double goal_speed_mps = 0.3;
  // The heading reference turns at up to this rate [rad/s] towards the goal's bearing, but, when
  // the reference is faster than travel_heading_min_speed_mps, no farther than
  // max_travel_off_heading_rad from the direction of travel (ForestHeadingTarget). Beyond the
  // paper (psi = 0): with paths only in seen space a goal beside the field of view could not be
  // approached; and a heading that turned towards the goal whatever the spline in flight turned
  // the camera away from where the vehicle went (layout 21 flew 75 deg off its camera axis into a
  // trunk). A heading that only followed the travel lost the goal (a single-trunk course flew
  // off sideways). 0: fixed heading. When the goal's bearing is more than
  // max_travel_off_heading_rad + the selector's max_bearing_rad from the direction of travel, no
  // heading the rule allows shows it, no path can reach towards it and each new path only turns
  // the travel as far as the camera sees: the vehicle stops and turns to face the goal before it
  // plans again (`turns_to_goal`; with the flight controller's torque observer, a course round
  // one trunk flew past its goal this way and never turned back).
  double max_yaw_rate_radps = 0.5;
  double travel_heading_min_speed_mps = 0.3;
  double max_travel_off_heading_rad = 0.5;  // inside the camera's +-45 deg, with a margin
  // Recovery (beyond the paper, which has none): when no new spline was adopted for
  // recovery_after_s while the vehicle is at rest (the spline flown out, the estimated speed
  // below rest_speed_mps, the heading settled), the vehicle backs off along the path it has flown
  // (free: it was just there) for up to recovery_backoff_m with its heading held, so that an
  // obstacle the depth model puts too close is seen from farther. Without recovery_min_backoff_m
  // of flown path behind it (at the start) it looks aside instead: the heading turns
  // recovery_look_aside_rad to one side of the goal's bearing, the other side at the next stall,
  // which moves seen space without moving the vehicle. recovery_after_s = 1e9: no recovery.
  double recovery_after_s = 1.0;
  double rest_speed_mps = 0.1;
  double recovery_backoff_m = 1.0;
  double recovery_min_backoff_m = 0.3;
  // 69 deg: beyond the +-45 deg field of view, so a phantom trunk ahead leaves the windows of
  // paths straight out (0.6 rad did not get the vehicle past a trunk 2 m ahead of the start).
  double recovery_look_aside_rad = 1.2;

  void Validate() const;  // std::invalid_argument naming the field
};

// Within this horizontal distance of the goal its bearing swings with the estimate: the heading
// is held [m].
constexpr double kHeadingHoldWithinM = 1.0;
// ForestMission plans no spline shorter than this per spline interval [m].
constexpr double kMinSplineIntervalM = 0.05;

// The bearing in W [rad] ForestMission's heading reference turns towards (at up to
// ForestMissionParams::max_yaw_rate_radps): nullopt (hold it) while backing off or within
// hold_within_m of the goal horizontally (its bearing swings there). Faster than
// travel_min_speed_mps horizontally (v_reference_W): the goal's bearing from p_W, but at most
// max_travel_off_heading_rad from the direction of travel, so the camera sees where the vehicle
// goes. Slower: look_aside_rad when a look-aside recovery set it, else the goal's bearing.
std::optional<double> ForestHeadingTarget(const Eigen::Vector3d& p_W, const Eigen::Vector3d& goal_W,
                                          const Eigen::Vector3d& v_reference_W,
                                          double travel_min_speed_mps,
                                          double max_travel_off_heading_rad,
                                          std::optional<double> look_aside_rad, bool backing_off,
                                          double hold_within_m = kHeadingHoldWithinM);

// True when the goal has left what ForestHeadingTarget can show: the reference flies faster than
// travel_min_speed_mps horizontally, the goal is farther than kHeadingHoldWithinM and its bearing
// is more than max_travel_off_heading_rad + max_bearing_rad (the seen wedge's half angle) from the
// direction of travel. ForestMission then stops and turns to the goal.
bool GoalLeftTheView(const Eigen::Vector3d& p_W, const Eigen::Vector3d& goal_W,
                     const Eigen::Vector3d& v_reference_W, double travel_min_speed_mps,
                     double max_travel_off_heading_rad, double max_bearing_rad);

// What one frame did (the per-frame figures of `aperture bench mononav`).
struct ForestFrameRecord {
  double t_s = 0.0;
  double perception_s = 0.0;  // thread CPU time of the front end (depth estimate)
  double planning_s = 0.0;    // thread CPU time of EDT, selection and the spline
  int segments = 0;
  int replans = 0;            // segments rejected by their spatial windows (Table II)
  bool selected = false;      // the waypoint selector ran (not the direct path to the goal)
  bool planned = false;       // a new spline was adopted
  bool direct = false;        // straight to the goal
  bool backed_off = false;    // a recovery: backing off along the flown path started
  bool looked_aside = false;  // a recovery: the heading started turning aside
  bool turned_to_goal = false;  // the goal left the view: stopping to turn towards it began
};

class ForestMission : public perception::Autopilot {
 public:
  // camera: the forward camera's model; T_BC its mount; vehicle: the controller's model; model:
  // the depth classifier (perception::DefaultMonoDepthModel() ships). Throws
  // std::invalid_argument for invalid params, a null camera or a non-rigid T_BC.
  ForestMission(const ForestMissionParams& params,
                std::shared_ptr<const perception::CameraModel> camera,
                const Eigen::Isometry3d& T_BC, const control::VehicleParameters& vehicle,
                perception::MonoDepthModel model);

  std::string name() const override { return "forest_mission"; }
  void OnImu(const perception::ImuSample& sample) override;
  void OnFrame(const perception::Frame& frame) override;
  // A body pose from the vehicle's odometry source (X = B: p_BX = 0, q_BX = identity).
  void OnOdometry(const perception::PoseMeasurement& pose_WB);
  perception::AutopilotCommand Step(double t_s) override;
  std::string status() const override;
  // Depth map and chosen path of the latest frame onto the onboard image (CV_8UC3).
  void DrawOverlay(cv::Mat& bgr) const;

  // The filter's estimate (t_s = latest IMU sample); nullopt before the first odometry pose.
  std::optional<control::QuadState> estimate() const;
  double heading_rad() const { return heading_rad_; }  // the heading reference psi [rad]
  // The selector's parameters: the mission's, max_bearing_rad narrowed to the camera's view.
  const WaypointSelectorParams& selector_params() const { return selector_.params(); }
  const std::vector<ForestFrameRecord>& frames() const { return frames_; }
  int replans() const;              // sum of ForestFrameRecord::replans
  int selections() const;           // frames that ran the waypoint selector
  int frames_replanned() const;     // frames whose first segment tried was rejected
  int frames_without_path() const;  // frames that found no traversable segment
  int back_offs() const;            // frames that started a back-off along the flown path
  int look_asides() const;          // frames that started a look-aside
  int turns_to_goal() const;        // frames that started a stop to turn towards the goal
  // The flown path kept for backing off (estimated positions kTrailSpacingM apart; a back-off
  // consumes what it flies back over).
  const FlownTrail& trail() const { return trail_; }
  bool goal_reached() const { return goal_reached_; }
  const perception::PoseFusionCounts& fusion_counts() const { return fusion_.counts(); }

 private:
  // The reference of the current spline at t_s (the hold point before the first one).
  control::TrajectoryPoint Reference(double t_s) const;
  void Plan(double t_s, const perception::MonoDepthEstimate& depth, ForestFrameRecord* record);
  // Turns heading_rad_ towards target_rad, at most max_yaw_rate_radps * dt_s.
  void TurnHeading(std::optional<double> target_rad, double dt_s);
  static constexpr double kTrailSpacingM = 0.1;
  // At rest: the current spline flown out, the estimated speed below rest_speed_mps, the heading
  // within kHeadingSettledRad of its target (the goal's bearing jitters with the estimate).
  bool AtRest(double t_s, const control::QuadState& x) const;
  static constexpr double kHeadingSettledRad = 0.05;
  // After a frame without a new spline: starts a recovery when the vehicle has stalled (see
  // ForestMissionParams::recovery_after_s).
  void Recover(double t_s, const control::QuadState& x, ForestFrameRecord* record);
  // Starts a stop and a turn towards the goal when the goal has left what the heading rule can
  // show (see max_yaw_rate_radps); true while that turn lasts (no planning then).
  bool TurnToGoal(double t_s, const control::QuadState& x, ForestFrameRecord* record);
  static constexpr double kTravelLookAheadS = 0.5;
  // Spline from the current reference (or estimate) along path_W; false when the solver fails.
  bool FollowPath(double t_s, const control::QuadState& x,
                  const std::vector<Eigen::Vector3d>& path_W);

  ForestMissionParams params_;
  std::shared_ptr<const perception::CameraModel> camera_;
  Eigen::Isometry3d T_BC_;
  control::VehicleParameters vehicle_;
  perception::FrontEndRunner front_ends_;
  WaypointSelector selector_;
  control::PositionController controller_;
  perception::PoseFusion fusion_;

  std::optional<control::TrajectoryPoint> hold_;  // before the first spline: the start pose
  std::optional<BSpline> spline_;
  double spline_start_t_s_ = 0.0;
  double heading_rad_ = 0.0;
  double heading_rate_radps_ = 0.0;
  double heading_error_rad_ = 0.0;  // to the heading target after the latest turn
  double last_step_t_s_ = 0.0;
  double still_since_t_s_ = 0.0;          // the vehicle has been at rest with no new spline since
  bool backing_off_ = false;              // the current spline backs off along the trail
  bool turning_to_goal_ = false;          // stopping and turning towards the goal (no planning)
  std::optional<double> look_aside_rad_;  // the heading of a look-aside recovery
  int look_aside_side_ = -1;              // +1 left, -1 right of the goal's bearing
  FlownTrail trail_{kTrailSpacingM};
  bool goal_reached_ = false;
  std::vector<Eigen::Vector3d> last_path_W_;                     // drawn by DrawOverlay
  Eigen::Isometry3d last_T_WB_ = Eigen::Isometry3d::Identity();  // estimate at the latest plan
  std::vector<ForestFrameRecord> frames_;
};

}  // namespace aperture::planning
