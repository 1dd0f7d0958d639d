#pragma once
// Configuration description (Serialize, config/param_archive.h) of GapDetectorParams: keys = field
// names, e.g. `outer_size_m: [1.3, 0.78]`, `--set gap.canny_high=100`; absent keys keep their
// defaults, unknown keys are rejected with the known keys, and the loaded struct is validated
// (ValidateGapDetectorParams). LoadParams(reader, &params) loads, config::DumpParams dumps.
#include "config/yaml_read_archive.h"
#include "perception/gap/gap_detector.h"

namespace aperture::perception {

template <typename Archive>
void Serialize(Archive* a, GapDetectorParams* p) {
  a->Visit(APERTURE_NVP(p, opening_size_m));
  a->Visit(APERTURE_NVP(p, inner_size_m));
  a->Visit(APERTURE_NVP(p, outer_size_m));
  a->Visit(APERTURE_NVP(p, canny_low));
  a->Visit(APERTURE_NVP(p, canny_high));
  a->Visit(APERTURE_NVP(p, min_perimeter_px));
  a->Visit(APERTURE_NVP(p, approx_epsilon_ratio));
  a->Visit(APERTURE_NVP(p, approx_epsilon_max_ratio));
  a->Visit(APERTURE_NVP(p, min_side_px));
  a->Visit(APERTURE_NVP(p, area_ratio_tolerance));
  a->Visit(APERTURE_NVP(p, min_contrast));
  a->Visit(APERTURE_NVP(p, edge_search_px));
  a->Visit(APERTURE_NVP(p, edge_sample_step_px));
  a->Visit(APERTURE_NVP(p, max_samples_per_side));
  a->Visit(APERTURE_NVP(p, corner_exclusion));
  a->Visit(APERTURE_NVP(p, max_corner_rms_px));
  a->Visit(APERTURE_NVP(p, pixel_sigma_px));
  a->Visit(APERTURE_NVP(p, refinement_iterations));
  a->Visit(APERTURE_NVP(p, use_roi));
  a->Visit(APERTURE_NVP(p, roi_margin_ratio));
  a->Visit(APERTURE_NVP(p, roi_margin_px));
}

// Validation hook of the loader (config::ValidateLoaded).
inline void ValidateParams(const GapDetectorParams& params) { ValidateGapDetectorParams(params); }

}  // namespace aperture::perception
