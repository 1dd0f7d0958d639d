#pragma once
// YAML loader (config::ParamReader, STYLE.md 6) for ForestMissionParams, the `mission` section of
// `aperture sim forest` (`--set mission.ego_dynamic=false`). Keys are the field names; absent keys
// keep the defaults (or what the caller set, e.g. the scenario's goal); unknown keys are rejected
// with their location and the known keys.
//
//   mission:
//     ego_dynamic: true                 # false: Table IV's baseline without the EDT
//     waypoint_order: optimal           # optimal | random (Table II's baseline)
//     random_seed: 0
//     max_speed_mps: 2.0                # DynamicLimits: speed, per-axis acceleration and jerk
//     max_acceleration_mps2: 2.0
//     max_jerk_mps3: 6.93
//     ground_height_m: 0.0
//     ground_clearance_m: 0.3
//     spline_path_points: 8
//     replan_from_estimate_m: 0.5
//     extension_m: 4.0
//     direct_goal_distance_m: 4.0
//     goal_reached_m: 0.3
//     goal_speed_mps: 0.3
//     edt: {response_time_s: 0.3, max_deceleration_mps2: 3, depth_error_margin_m: 0.3}
//     waypoints: {cluster_tolerance_m: 0.35, vehicle_radius_m: 0.25, cycle_time_s: 0.3}
//
// Ends with ForestMissionParams::Validate(); throws std::invalid_argument naming the bad value.
#include "config/param_reader.h"
#include "planning/mono_nav/forest_mission.h"

namespace aperture::planning {

void LoadParams(config::ParamReader& reader, EgoDynamicParams* params);
void LoadParams(config::ParamReader& reader, WaypointSelectorParams* params);
void LoadParams(config::ParamReader& reader, ForestMissionParams* params);

}  // namespace aperture::planning
