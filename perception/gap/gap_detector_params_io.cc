#include "perception/gap/gap_detector_params_io.h"

namespace aperture::perception {

void LoadParams(config::ParamReader& reader, GapDetectorParams* params) {
  reader.Read("opening_size_m", &params->opening_size_m);
  reader.Read("inner_size_m", &params->inner_size_m);
  reader.Read("outer_size_m", &params->outer_size_m);
  reader.Read("canny_low", &params->canny_low);
  reader.Read("canny_high", &params->canny_high);
  reader.Read("min_perimeter_px", &params->min_perimeter_px);
  reader.Read("approx_epsilon_ratio", &params->approx_epsilon_ratio);
  reader.Read("min_side_px", &params->min_side_px);
  reader.Read("area_ratio_tolerance", &params->area_ratio_tolerance);
  reader.Read("min_contrast", &params->min_contrast);
  reader.Read("edge_search_px", &params->edge_search_px);
  reader.Read("edge_sample_step_px", &params->edge_sample_step_px);
  reader.Read("max_samples_per_side", &params->max_samples_per_side);
  reader.Read("corner_exclusion", &params->corner_exclusion);
  reader.Read("max_corner_rms_px", &params->max_corner_rms_px);
  reader.Read("pixel_sigma_px", &params->pixel_sigma_px);
  reader.Read("refinement_iterations", &params->refinement_iterations);
  reader.Read("use_roi", &params->use_roi);
  reader.Read("roi_margin_ratio", &params->roi_margin_ratio);
  reader.Read("roi_margin_px", &params->roi_margin_px);
  ValidateGapDetectorParams(*params);
}

}  // namespace aperture::perception
