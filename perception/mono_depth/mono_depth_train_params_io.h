#pragma once
// YAML loader (config::ParamReader, STYLE.md 6) for MonoDepthTrainParams: the keys are the field
// names, the feature fields flat beside them; unknown keys are rejected and the result validated.
//
//   work_width_px: 320   patch_px: 8   scale_factor: 3
//   min_depth_m: 0.5     max_depth_m: 40   labels: 16   row_bands: 6
//   log_epsilon: 1e-3    svm_c: 1.0   svm_tolerance: 0.01   patch_stride: 1
#include "config/param_reader.h"
#include "perception/mono_depth/mono_depth_trainer.h"

namespace aperture::perception {

void LoadParams(config::ParamReader& reader, MonoDepthTrainParams* params);

}  // namespace aperture::perception
