#pragma once
// Configuration description (Serialize, config/param_archive.h) of LedTrackerParams and its parts
// (thesis C.3-C.5): LoadParams(reader, &params) (config/yaml_read_archive.h) loads,
// config::DumpParams dumps. Keys are the field names.
//
//   tracker:
//     prediction_match_px: 5           # C.5 gate of the predicted LEDs
//     roi_half_size_px: 24
//     max_rms_px: 2
//     detector: {threshold: 120, smoothing_sigma_px: 0.8, min_area_px: 2, max_area_px: 2500,
//                min_fill_ratio: 0.3, max_aspect_ratio: 3, max_blobs: 10, centroid_floor: 20,
//                centroid_margin_px: 3}                                         # (C.1)-(C.4)
//     correspondence: {p3p_method: kneip, reprojection_threshold_px: 5, acceptance_ratio: 0.5,
//                      min_inlier_ratio: 0.75, min_subset_ratio: 0.7}          # Algorithm 1
//     refiner: {max_iterations: 10, step_tolerance: 1e-9, detection_sigma_px: 1}  # (C.8), (C.9)
//     near_prediction: {gate_px: 5}                # < 4 LEDs matched while tracking
//     max_near_prediction_rotation_sigma_deg: 30
//     labelling_margin_ratio: 2                    # fresh start: runner-up RMS / best RMS >=
#include "config/yaml_read_archive.h"
#include "perception/led/led_tracker.h"
#include "perception/led/p3p_solver.h"

namespace aperture::perception {

template <typename Archive>
void Serialize(Archive* a, LedDetectorParams* p) {
  a->Visit(APERTURE_NVP(p, threshold));
  a->Visit(APERTURE_NVP(p, smoothing_sigma_px));
  a->Visit(APERTURE_NVP(p, min_area_px));
  a->Visit(APERTURE_NVP(p, max_area_px));
  a->Visit(APERTURE_NVP(p, min_fill_ratio));
  a->Visit(APERTURE_NVP(p, max_aspect_ratio));
  a->Visit(APERTURE_NVP(p, max_blobs));
  a->Visit(APERTURE_NVP(p, centroid_floor));
  a->Visit(APERTURE_NVP(p, centroid_margin_px));
}

template <typename Archive>
void Serialize(Archive* a, LedCorrespondenceParams* p) {
  static const config::EnumNames<P3pMethod> kP3pMethods = {
      {P3pMethodName(P3pMethod::kKneip), P3pMethod::kKneip},
      {P3pMethodName(P3pMethod::kOpenGv), P3pMethod::kOpenGv},
      {P3pMethodName(P3pMethod::kAp3p), P3pMethod::kAp3p}};
  a->Visit(APERTURE_NVP(p, p3p_method), kP3pMethods);
  a->Visit(APERTURE_NVP(p, reprojection_threshold_px));
  a->Visit(APERTURE_NVP(p, acceptance_ratio));
  a->Visit(APERTURE_NVP(p, min_inlier_ratio));
  a->Visit(APERTURE_NVP(p, min_subset_ratio));
}

template <typename Archive>
void Serialize(Archive* a, LedPoseRefinerParams* p) {
  a->Visit(APERTURE_NVP(p, max_iterations));
  a->Visit(APERTURE_NVP(p, step_tolerance));
  a->Visit(APERTURE_NVP(p, detection_sigma_px));
}

template <typename Archive>
void Serialize(Archive* a, LedNearPredictionParams* p) {
  a->Visit(APERTURE_NVP(p, gate_px));
}

template <typename Archive>
void Serialize(Archive* a, LedTrackerParams* p) {
  a->Visit(APERTURE_NVP(p, detector));
  a->Visit(APERTURE_NVP(p, correspondence));
  a->Visit(APERTURE_NVP(p, refiner));
  a->Visit(APERTURE_NVP(p, prediction_match_px));
  a->Visit(APERTURE_NVP(p, roi_half_size_px));
  a->Visit(APERTURE_NVP(p, max_rms_px));
  a->Visit(APERTURE_NVP(p, near_prediction));
  a->Visit(APERTURE_NVP(p, max_near_prediction_rotation_sigma_deg));
  a->Visit(APERTURE_NVP(p, labelling_margin_ratio));
}

}  // namespace aperture::perception
