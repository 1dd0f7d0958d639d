#pragma once
// Tag detectors by name (`apriltag.detector=...`). The perception library registers its own
// ("apriltag"); the application adds detectors of higher layers (servo/'s "visp") before it
// registers the front ends:
//
//   TagDetectorRegistry detectors = TagDetectorRegistry::WithBuiltins();
//   detectors.Register("visp", &servo::CreateVispTagDetector);
//   RegisterBuiltinFrontEnds(front_ends, detectors);
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "perception/tags/tag_detector.h"

namespace aperture::perception {

class TagDetectorRegistry {
 public:
  // The detectors of the perception library: "apriltag" (AprilTagLibraryDetector).
  static TagDetectorRegistry WithBuiltins();

  // std::invalid_argument for an empty or repeated name or an empty factory.
  void Register(const std::string& name, TagDetectorFactory factory);
  std::vector<std::string> Names() const;  // sorted
  // Validates params, then builds; std::invalid_argument for an unknown name (listing the
  // known ones) or bad params.
  std::unique_ptr<TagDetector> Create(const std::string& name,
                                      const TagDetectorParams& params) const;

 private:
  std::map<std::string, TagDetectorFactory> factories_;
};

}  // namespace aperture::perception
