#include "perception/mono_depth/mono_depth_train_params_io.h"

namespace aperture::perception {

void LoadParams(config::ParamReader& reader, MonoDepthTrainParams* params) {
  reader.Read("work_width_px", &params->features.work_width_px);
  reader.Read("patch_px", &params->features.patch_px);
  reader.Read("scale_factor", &params->features.scale_factor);
  reader.Read("min_depth_m", &params->min_depth_m);
  reader.Read("max_depth_m", &params->max_depth_m);
  reader.Read("labels", &params->labels);
  reader.Read("row_bands", &params->row_bands);
  reader.Read("log_epsilon", &params->log_epsilon);
  reader.Read("svm_c", &params->svm_c);
  reader.Read("svm_tolerance", &params->svm_tolerance);
  reader.Read("patch_stride", &params->patch_stride);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

}  // namespace aperture::perception
