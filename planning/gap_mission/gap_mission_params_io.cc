#include "planning/gap_mission/gap_mission_params_io.h"

#include "perception/estimation/pose_imu_filter_params_io.h"
#include "perception/gap/gap_detector_params_io.h"
#include "planning/planning_params_io.h"

namespace aperture::planning {

void LoadParams(config::ParamReader& reader, GapMissionParams* params) {
  reader.Read("camera_id", &params->camera_id);
  reader.Read("init_detections", &params->init_detections);
  reader.Read("gravity_samples", &params->gravity_samples);
  reader.Read("detection_covariance_scale", &params->detection_covariance_scale);
  reader.Read("max_consecutive_rejections", &params->max_consecutive_rejections);
  reader.Read("min_ground_clearance_m", &params->min_ground_clearance_m);
  reader.Read("hover_s", &params->hover_s);
  reader.Read("init_max_relative_sigma", &params->init_max_relative_sigma);
  reader.Read("transfer_speed_mps", &params->transfer_speed_mps);
  reader.Read("min_transfer_s", &params->min_transfer_s);
  reader.Read("start_hold_s", &params->start_hold_s);
  reader.Read("lead_in_s", &params->lead_in_s);
  reader.Read("min_replan_remaining_s", &params->min_replan_remaining_s);
  reader.Read("detection_timeout_s", &params->detection_timeout_s);
  reader.Read("approach_commit_s", &params->approach_commit_s);
  reader.Read("recovered_hold_s", &params->recovered_hold_s);
  reader.ReadSection("detector", &params->detector);
  reader.ReadSection("filter", &params->filter);
  reader.ReadSection("traverse", &params->traverse);
  reader.ReadSection("approach", &params->approach);
  reader.ReadSection("fallback_limits", &params->fallback_limits);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

}  // namespace aperture::planning
