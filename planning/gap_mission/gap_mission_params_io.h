#pragma once
// Configuration description (Serialize, config/param_archive.h) of GapMissionParams, the `mission`
// section of `aperture sim gap` and `aperture bench gap` (`--set mission.hover_s=0.5`): loaded by
// LoadParams(reader, &params) (config/yaml_read_archive.h), dumped by config::DumpParams. Keys are
// the field names; absent keys keep the defaults (or what the caller set before, e.g. the
// scenario's pattern sizes); unknown keys are rejected with their location and the known keys.
//
//   mission:
//     hover_s: 1.0
//     transfer_speed_mps: 1.5
//     detector: {canny_low: 40}          # GapDetectorParams (perception/gap)
//     filter: {mahalanobis_gate: 22.46}  # PoseImuFilterParams (perception/estimation)
//     traverse: {max_start_speed_mps: 3} # TraverseParameters (planning)
//     approach: {duration_min_s: 1.0}    # ApproachPlannerParameters (planning)
//     fallback_limits: {max_body_rate_radps: 10}  # FeasibilityLimits of the second attempt
//     controller: {p_xy_per_s2: 5}       # PositionControllerParams, Table A.2 (control)
//     recovery: {max_vertical_speed_mps: 0.3, controller: {d_z_per_s: 6}}  # RecoveryParams, B.3.2
//
// Loading ends with GapMissionParams::Validate(); errors are std::invalid_argument naming where
// the bad value is.
#include "control/control_params_io.h"
#include "perception/estimation/pose_imu_filter_params_io.h"
#include "perception/gap/gap_detector_params_io.h"
#include "planning/gap_mission/gap_mission.h"
#include "planning/planning_params_io.h"

namespace aperture::planning {

template <typename Archive>
void Serialize(Archive* a, GapMissionParams* p) {
  a->Visit(APERTURE_NVP(p, camera_id));
  a->Visit(APERTURE_NVP(p, init_detections));
  a->Visit(APERTURE_NVP(p, gravity_samples));
  a->Visit(APERTURE_NVP(p, detection_covariance_scale));
  a->Visit(APERTURE_NVP(p, max_consecutive_rejections));
  a->Visit(APERTURE_NVP(p, min_ground_clearance_m));
  a->Visit(APERTURE_NVP(p, hover_s));
  a->Visit(APERTURE_NVP(p, init_max_relative_sigma));
  a->Visit(APERTURE_NVP(p, transfer_speed_mps));
  a->Visit(APERTURE_NVP(p, min_transfer_s));
  a->Visit(APERTURE_NVP(p, start_hold_s));
  a->Visit(APERTURE_NVP(p, lead_in_s));
  a->Visit(APERTURE_NVP(p, min_replan_remaining_s));
  a->Visit(APERTURE_NVP(p, detection_timeout_s));
  a->Visit(APERTURE_NVP(p, approach_commit_s));
  a->Visit(APERTURE_NVP(p, recovered_hold_s));
  a->Visit(APERTURE_NVP(p, recovery_odometry_delay_s));
  a->Visit(APERTURE_NVP(p, recovery_odometry_alignment_poses));
  a->Visit(APERTURE_NVP(p, recovery_odometry_velocity_sigma_mps));
  a->VisitLimit(APERTURE_NVP(p, recovery_range_sigma_m));
  a->Visit(APERTURE_NVP(p, recovery_max_process_noise_scale));
  a->Visit(APERTURE_NVP(p, detector));
  a->Visit(APERTURE_NVP(p, filter));
  a->Visit(APERTURE_NVP(p, traverse));
  a->Visit(APERTURE_NVP(p, approach));
  a->Visit(APERTURE_NVP(p, fallback_limits));
  a->Visit(APERTURE_NVP(p, controller));
  a->Visit(APERTURE_NVP(p, recovery));
}

}  // namespace aperture::planning
