#pragma once
// Configuration descriptions (Serialize, config/param_archive.h) of ForestMissionParams and its
// components, the `mission` section of `aperture sim forest` (`--set mission.ego_dynamic=false`):
// LoadParams(reader, &params) loads (config/yaml_read_archive.h), config::DumpParams dumps. Keys
// are the field names; absent keys keep the defaults (or what the caller set, e.g. the scenario's
// goal); unknown keys are rejected with their location and the known keys; the loaded struct is
// validated.
//
//   mission:
//     goal_W: [22, 0, 1.5]              # the flight sets it from forest.goal_m
//     ego_dynamic: true                 # false: Table IV's baseline without the EDT
//     waypoint_order: optimal           # optimal | random (Table II's baseline)
//     random_seed: 0
//     limits: {max_speed_mps: 2.0, max_acceleration_mps2: [2, 2, 2], max_jerk_mps3: [20.8, ...]}
//     spline: {samples_per_interval: 4, dense_samples: 400, ...}
//     edt: {response_time_s: 0.3, max_deceleration_mps2: 3, depth_error_margin_m: 0.3}
//     waypoints: {cluster_tolerance_m: 0.35, vehicle_radius_m: 0.25, max_height_from_goal_m: 0}
//     controller: {...}                 # control::PositionControllerParams
//     fusion: {filter: {...}, max_consecutive_rejections: 3}
//     camera_id: 0
//     ground_height_m: 0.0
//     ground_clearance_m: 0.3
//     spline_path_points: 6
//     replan_from_estimate_m: 0.5
//     extension_m: 4.0
//     extension_standoff_m: 1.5
//     direct_goal_distance_m: 4.0
//     goal_reached_m: 0.3
//     goal_speed_mps: 0.3
//     max_yaw_rate_radps: 0.5
//     travel_heading_min_speed_mps: 0.3  # above: the heading stays within
//     max_travel_off_heading_rad: 0.5     #   this of the travel; below: towards the goal
//     recovery_after_s: 1.0               # at rest this long without a spline: recover
//     rest_speed_mps: 0.1
//     recovery_backoff_m: 1.0             # back off this far along the flown path
//     recovery_min_backoff_m: 0.3         # less flown path behind: look aside instead
//     recovery_look_aside_rad: 1.2
#include "config/yaml_read_archive.h"
#include "control/control_params_io.h"
#include "perception/estimation/pose_fusion_params_io.h"
#include "planning/mono_nav/forest_mission.h"

namespace aperture::planning {

template <typename Archive>
void Serialize(Archive* a, EgoDynamicParams* p) {
  a->Visit(APERTURE_NVP(p, response_time_s));
  a->Visit(APERTURE_NVP(p, max_deceleration_mps2));
  a->Visit(APERTURE_NVP(p, depth_error_margin_m));
}

template <typename Archive>
void Serialize(Archive* a, WaypointSelectorParams* p) {
  a->Visit(APERTURE_NVP(p, cluster_tolerance_m));
  a->Visit(APERTURE_NVP(p, min_cluster_points));
  a->Visit(APERTURE_NVP(p, cycle_time_s));
  a->Visit(APERTURE_NVP(p, min_collision_threshold_m));
  a->Visit(APERTURE_NVP(p, vehicle_radius_m));
  a->Visit(APERTURE_NVP(p, state_sigma_m));
  a->Visit(APERTURE_NVP(p, path_samples));
  a->Visit(APERTURE_NVP(p, max_height_from_goal_m));
  a->Visit(APERTURE_NVP(p, max_bearing_rad));
  a->Visit(APERTURE_NVP(p, seen_from_m));
}

template <typename Archive>
void Serialize(Archive* a, DynamicLimits* p) {
  a->Visit(APERTURE_NVP(p, max_speed_mps));
  a->Visit(APERTURE_NVP(p, max_acceleration_mps2));
  a->Visit(APERTURE_NVP(p, max_jerk_mps3));
}

template <typename Archive>
void Serialize(Archive* a, MinTimeBSplineParams* p) {
  a->Visit(APERTURE_NVP(p, samples_per_interval));
  a->Visit(APERTURE_NVP(p, nlopt_relative_tolerance));
  a->Visit(APERTURE_NVP(p, nlopt_max_evaluations));
  a->Visit(APERTURE_NVP(p, dense_samples));
  a->Visit(APERTURE_NVP(p, saturation_tolerance));
  a->Visit(APERTURE_NVP(p, max_refits));
}

template <typename Archive>
void Serialize(Archive* a, ForestMissionParams* p) {
  a->Visit(APERTURE_NVP(p, goal_W));
  a->Visit(APERTURE_NVP(p, ego_dynamic));
  a->Visit(APERTURE_NVP(p, waypoint_order),
           config::EnumNames<WaypointOrder>{{"optimal", WaypointOrder::kOptimal},
                                            {"random", WaypointOrder::kRandom}});
  a->Visit(APERTURE_NVP(p, random_seed));
  a->Visit(APERTURE_NVP(p, limits));
  a->Visit(APERTURE_NVP(p, spline));
  a->Visit(APERTURE_NVP(p, edt));
  a->Visit(APERTURE_NVP(p, waypoints));
  a->Visit(APERTURE_NVP(p, controller));
  a->Visit(APERTURE_NVP(p, fusion));
  a->Visit(APERTURE_NVP(p, camera_id));
  a->Visit(APERTURE_NVP(p, ground_height_m));
  a->Visit(APERTURE_NVP(p, ground_clearance_m));
  a->Visit(APERTURE_NVP(p, spline_path_points));
  a->Visit(APERTURE_NVP(p, replan_from_estimate_m));
  a->Visit(APERTURE_NVP(p, extension_m));
  a->Visit(APERTURE_NVP(p, extension_standoff_m));
  a->Visit(APERTURE_NVP(p, direct_goal_distance_m));
  a->Visit(APERTURE_NVP(p, goal_reached_m));
  a->Visit(APERTURE_NVP(p, goal_speed_mps));
  a->Visit(APERTURE_NVP(p, max_yaw_rate_radps));
  a->Visit(APERTURE_NVP(p, travel_heading_min_speed_mps));
  a->Visit(APERTURE_NVP(p, max_travel_off_heading_rad));
  a->Visit(APERTURE_NVP(p, recovery_after_s));
  a->Visit(APERTURE_NVP(p, rest_speed_mps));
  a->Visit(APERTURE_NVP(p, recovery_backoff_m));
  a->Visit(APERTURE_NVP(p, recovery_min_backoff_m));
  a->Visit(APERTURE_NVP(p, recovery_look_aside_rad));
}

}  // namespace aperture::planning
