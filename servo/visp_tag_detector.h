#pragma once
// TagDetector on ViSP's vpDetectorAprilTag (ViSP 3.5, which embeds its own copy of the apriltag
// library), for benchmarking side by side with perception's AprilTagLibraryDetector. Registered
// by the application as detector "visp" (`apriltag.detector=visp`); ViSP types stay in the .cc.
//
// Mapping of TagDetectorParams: one vpDetectorAprilTag per family; quad_decimate, quad_sigma,
// threads, refine_edges and decode_sharpening are passed on; min_white_black_diff is not (ViSP
// 3.5 has no setter: its copy of the library keeps 5). ViSP 3.5 reports neither the
// decision margin nor the corrected bits: decision_margin is NaN and hamming 0, so
// min_decision_margin > 0 and max_hamming < 2 (ViSP decodes with up to 2 corrected bits) are
// rejected. Corners come in the library's order, shifted to OpenCV pixel centres like
// AprilTagLibraryDetector's.
#include <memory>

#include "perception/tags/tag_detector.h"

namespace aperture::servo {

inline constexpr const char* kVispTagDetectorName = "visp";

// std::invalid_argument for a family this ViSP build lacks (Debian's disables tagStandard41h12,
// tagStandard52h13, tagCircle49h12, tagCustom48h12) or the settings above.
std::unique_ptr<perception::TagDetector> CreateVispTagDetector(
    const perception::TagDetectorParams& params);

}  // namespace aperture::servo
