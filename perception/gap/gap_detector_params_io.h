#pragma once
// Loads GapDetectorParams from a config section (keys = field names, e.g. `outer_size_m: [1.3,
// 0.78]`, `--set gap.canny_high=100`); absent keys keep their defaults. Unknown keys are left to
// the caller's RejectUnknownKeys (the front-end registry rejects them); invalid values throw
// std::invalid_argument (ValidateGapDetectorParams).
#include "config/param_reader.h"
#include "perception/gap/gap_detector.h"

namespace aperture::perception {

void LoadParams(config::ParamReader& reader, GapDetectorParams* params);

}  // namespace aperture::perception
