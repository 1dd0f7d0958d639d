#pragma once
// Configuration description (Serialize, config/param_archive.h) of PoseFusionParams: the filter's
// parameters (pose_imu_filter_params_io.h) and the restart policy.
//
//   fusion:
//     filter: {accel_noise_density: 3.9e-3, mahalanobis_gate: 22.46, ...}
//     max_consecutive_rejections: 3
//     max_restart_rotation_rad: 0.5
#include "perception/estimation/pose_fusion.h"
#include "perception/estimation/pose_imu_filter_params_io.h"

namespace aperture::perception {

template <typename Archive>
void Serialize(Archive* a, PoseFusionParams* p) {
  a->Visit(APERTURE_NVP(p, filter));
  a->Visit(APERTURE_NVP(p, max_consecutive_rejections));
  a->Visit(APERTURE_NVP(p, max_restart_rotation_rad));
}

}  // namespace aperture::perception
