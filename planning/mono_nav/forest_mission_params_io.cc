#include "planning/mono_nav/forest_mission_params_io.h"

namespace aperture::planning {

void LoadParams(config::ParamReader& reader, EgoDynamicParams* params) {
  reader.Read("response_time_s", &params->response_time_s);
  reader.Read("max_deceleration_mps2", &params->max_deceleration_mps2);
  reader.Read("depth_error_margin_m", &params->depth_error_margin_m);
}

void LoadParams(config::ParamReader& reader, WaypointSelectorParams* params) {
  reader.Read("cluster_tolerance_m", &params->cluster_tolerance_m);
  reader.Read("min_cluster_points", &params->min_cluster_points);
  reader.Read("cycle_time_s", &params->cycle_time_s);
  reader.Read("min_collision_threshold_m", &params->min_collision_threshold_m);
  reader.Read("vehicle_radius_m", &params->vehicle_radius_m);
  reader.Read("state_sigma_m", &params->state_sigma_m);
  reader.Read("path_samples", &params->path_samples);
  reader.Read("max_height_from_goal_m", &params->max_height_from_goal_m);
}

void LoadParams(config::ParamReader& reader, ForestMissionParams* params) {
  reader.Read("ego_dynamic", &params->ego_dynamic);
  reader.ReadEnum("waypoint_order", &params->waypoint_order,
                  {{"optimal", WaypointOrder::kOptimal}, {"random", WaypointOrder::kRandom}});
  reader.Read("random_seed", &params->random_seed);
  reader.Read("max_speed_mps", &params->limits.max_speed_mps);
  if (reader.Has("max_acceleration_mps2")) {
    double value = 0.0;
    reader.Read("max_acceleration_mps2", &value);
    params->limits.max_acceleration_mps2.setConstant(value);
  }
  if (reader.Has("max_jerk_mps3")) {
    double value = 0.0;
    reader.Read("max_jerk_mps3", &value);
    params->limits.max_jerk_mps3.setConstant(value);
  }
  reader.Read("camera_id", &params->camera_id);
  reader.Read("ground_height_m", &params->ground_height_m);
  reader.Read("ground_clearance_m", &params->ground_clearance_m);
  reader.Read("spline_path_points", &params->spline_path_points);
  reader.Read("replan_from_estimate_m", &params->replan_from_estimate_m);
  reader.Read("extension_m", &params->extension_m);
  reader.Read("direct_goal_distance_m", &params->direct_goal_distance_m);
  reader.Read("goal_reached_m", &params->goal_reached_m);
  reader.Read("goal_speed_mps", &params->goal_speed_mps);
  reader.ReadSection("edt", &params->edt);
  reader.ReadSection("waypoints", &params->waypoints);
  reader.Validate(*params);
}

}  // namespace aperture::planning
