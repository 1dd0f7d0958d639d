#include "perception/tags/tag_detector.h"

#include <stdexcept>

#include "perception/tags/apriltag_family.h"

namespace aperture::perception {

void TagDetectorParams::Validate() const {
  auto fail = [](const std::string& message) {
    throw std::invalid_argument("tag detector: " + message);
  };
  if (families.empty()) fail("families is empty; give at least one, e.g. [tag36h11]");
  for (const std::string& family : families) CanonicalAprilTagFamilyName(family);
  if (!(quad_decimate >= 1.0)) {
    fail("quad_decimate = " + std::to_string(quad_decimate) + " must be >= 1 (1 = full image)");
  }
  if (!(quad_sigma >= 0.0)) fail("quad_sigma = " + std::to_string(quad_sigma) + " must be >= 0");
  if (threads < 1) fail("threads = " + std::to_string(threads) + " must be >= 1");
  if (max_hamming < 0 || max_hamming > 3) {
    fail("max_hamming = " + std::to_string(max_hamming) + " must be in [0, 3]");
  }
  if (min_white_black_diff < 0 || min_white_black_diff > 255) {
    fail("min_white_black_diff = " + std::to_string(min_white_black_diff) +
         " must be in [0, 255] (gray levels)");
  }
  if (!(decode_sharpening >= 0.0) || !(min_decision_margin >= 0.0)) {
    fail("decode_sharpening and min_decision_margin must be >= 0");
  }
}

}  // namespace aperture::perception
