#pragma once
// YAML loader (config::ParamReader, STYLE.md 6) of GapflytMissionParams, the `mission` section of
// `aperture sim gapflyt` (`--set mission.key=value`). Keys are the field names; absent keys keep
// the defaults; unknown keys are rejected with their location.
//
//   mission:
//     settle_s: 1.0
//     scan_direction: [1, 1]      # (left, up) of the start
//     scan_speed_mps: 0.6
//     scan_ramp_s: 0.5
//     scan_cruise_s: 0.6
//     max_scans: 3
//     commit_area_fraction: 0.3
//     commit_depth_m: 1.0
//     commit_error: 0.1
//     commit_max_error_rate: 0.1
//     commit_rate_window_s: 0.2
//     commit_border_px: 4
//     commit_max_aim_offset_m: 0.35
//     max_servo_s: 8.0
//     max_servo_speed_mps: 1.2
//     max_servo_accel_mps2: 1.0
//     go_through_speed_mps: 1.0
//     max_aim_correction_m: 0.25   # 0 = straight ahead from the commit (the paper)
//     body_radius_m: 0.08
//     propeller_radius_m: 0.0635
//     go_through_distance_m: 1.8
//     stop_hold_s: 1.0
//     max_lost_frames: 3
//     odometry: {velocity_time_constant_s: 0.3, max_correction_noise: 0.075, calibration_s: 0.5,
//                wind_gate_mps: 0.4,
//                wind_gate_sigmas: 5, wind_residual_time_constant_s: 0.1, max_wind_coast_s: 1.5}
//     ts2p: {...}          # Ts2pNodeParams (perception/ts2p/ts2p_node.h); interval is ignored
//     gap_tracker: {...}   # LabelTrackerParams (perception/ts2p/label_tracker.h)
//     servo: {law: moments | pid, moments: {...}, pid: {...}}   # servo/servo_params_io.h
#include "config/param_reader.h"
#include "planning/gapflyt/gapflyt_mission.h"

namespace aperture::planning {

// Throws std::invalid_argument naming the key for unknown keys or invalid values.
void LoadParams(config::ParamReader& reader, GapflytMissionParams* params);

}  // namespace aperture::planning
