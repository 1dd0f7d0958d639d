#pragma once
// Configuration description (Serialize, config/param_archive.h) of PoseHoldParams (the position
// hold on fused poses + IMU of the LED hover): LoadParams(reader, &params) loads
// (config/yaml_read_archive.h), config::DumpParams dumps; loading ends with Validate().
//
//   hold:
//     filter: {mahalanobis_gate: 22.46}          # PoseImuFilterParams
//     controller: {p_xy_per_s2: 5, d_xy_per_s: 4}  # PositionControllerParams, Table A.2
//     integral_gain_per_s3: 3
//     max_integral_accel_mps2: 2
//     max_integrated_error_m: 0.05
//     disturbance_time_constant_s: 0.1
//     max_disturbance_accel_mps2: 3
//     max_position_error_m: 1
//     max_pose_age_s: 0.5
//     max_consecutive_rejections: 3
//     max_process_noise_scale: 100
#include "control/control_params_io.h"
#include "perception/estimation/pose_imu_filter_params_io.h"
#include "planning/pose_hold.h"

namespace aperture::planning {

template <typename Archive>
void Serialize(Archive* a, PoseHoldParams* p) {
  a->Visit(APERTURE_NVP(p, filter));
  a->Visit(APERTURE_NVP(p, controller));
  a->Visit(APERTURE_NVP(p, integral_gain_per_s3));
  a->Visit(APERTURE_NVP(p, max_integral_accel_mps2));
  a->Visit(APERTURE_NVP(p, max_integrated_error_m));
  a->Visit(APERTURE_NVP(p, disturbance_time_constant_s));
  a->Visit(APERTURE_NVP(p, max_disturbance_accel_mps2));
  a->Visit(APERTURE_NVP(p, max_position_error_m));
  a->Visit(APERTURE_NVP(p, max_pose_age_s));
  a->Visit(APERTURE_NVP(p, max_consecutive_rejections));
  a->Visit(APERTURE_NVP(p, max_process_noise_scale));
}

}  // namespace aperture::planning
