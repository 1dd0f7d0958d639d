#include "planning/gapflyt/gapflyt_mission_params_io.h"

#include "perception/ts2p/label_tracker.h"
#include "perception/ts2p/ts2p_node.h"
#include "servo/servo_params_io.h"

namespace aperture::planning {
namespace {

void LoadOdometry(config::ParamReader& reader, control::DragAidedOdometryParams* params) {
  reader.Read("velocity_time_constant_s", &params->velocity_time_constant_s);
  reader.Read("max_correction_noise", &params->max_correction_noise);
  reader.Read("calibration_s", &params->calibration_s);
  reader.Read("wind_residual_time_constant_s", &params->wind_residual_time_constant_s);
  reader.Read("wind_gate_mps", &params->wind_gate_mps);
  reader.Read("wind_gate_sigmas", &params->wind_gate_sigmas);
  reader.Read("max_wind_coast_s", &params->max_wind_coast_s);
  reader.RejectUnknownKeys();
}

}  // namespace

void LoadParams(config::ParamReader& reader, GapflytMissionParams* params) {
  reader.Read("settle_s", &params->settle_s);
  reader.Read("scan_direction", &params->scan_direction);
  reader.Read("scan_speed_mps", &params->scan_speed_mps);
  reader.Read("scan_ramp_s", &params->scan_ramp_s);
  reader.Read("scan_cruise_s", &params->scan_cruise_s);
  reader.Read("max_scans", &params->max_scans);
  reader.Read("commit_area_fraction", &params->commit_area_fraction);
  reader.Read("commit_depth_m", &params->commit_depth_m);
  reader.Read("commit_error", &params->commit_error);
  reader.Read("commit_max_error_rate", &params->commit_max_error_rate);
  reader.Read("commit_rate_window_s", &params->commit_rate_window_s);
  reader.Read("commit_border_px", &params->commit_border_px);
  reader.Read("commit_max_aim_offset_m", &params->commit_max_aim_offset_m);
  reader.Read("max_servo_s", &params->max_servo_s);
  reader.Read("max_servo_speed_mps", &params->max_servo_speed_mps);
  reader.Read("max_servo_accel_mps2", &params->max_servo_accel_mps2);
  reader.Read("go_through_speed_mps", &params->go_through_speed_mps);
  reader.Read("max_aim_correction_m", &params->max_aim_correction_m);
  reader.Read("body_radius_m", &params->body_radius_m);
  reader.Read("propeller_radius_m", &params->propeller_radius_m);
  reader.Read("go_through_distance_m", &params->go_through_distance_m);
  reader.Read("stop_hold_s", &params->stop_hold_s);
  reader.Read("max_lost_frames", &params->max_lost_frames);
  if (reader.Has("odometry")) {
    config::ParamReader odometry = reader.Section("odometry");
    LoadOdometry(odometry, &params->odometry);
  }
  reader.ReadSection("ts2p", &params->ts2p);
  reader.ReadSection("gap_tracker", &params->tracker);
  reader.ReadSection("servo", &params->servo);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

}  // namespace aperture::planning
