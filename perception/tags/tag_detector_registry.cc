#include "perception/tags/tag_detector_registry.h"

#include <stdexcept>

#include "perception/tags/apriltag_library_detector.h"

namespace aperture::perception {

TagDetectorRegistry TagDetectorRegistry::WithBuiltins() {
  TagDetectorRegistry registry;
  registry.Register(AprilTagLibraryDetector::kName, [](const TagDetectorParams& params) {
    return std::make_unique<AprilTagLibraryDetector>(params);
  });
  return registry;
}

void TagDetectorRegistry::Register(const std::string& name, TagDetectorFactory factory) {
  if (name.empty()) throw std::invalid_argument("TagDetectorRegistry: empty detector name");
  if (!factory)
    throw std::invalid_argument("TagDetectorRegistry: empty factory for '" + name + "'");
  if (!factories_.emplace(name, std::move(factory)).second) {
    throw std::invalid_argument("TagDetectorRegistry: detector '" + name + "' registered twice");
  }
}

std::vector<std::string> TagDetectorRegistry::Names() const {
  std::vector<std::string> names;
  for (const auto& [name, factory] : factories_) names.push_back(name);
  return names;
}

std::unique_ptr<TagDetector> TagDetectorRegistry::Create(const std::string& name,
                                                         const TagDetectorParams& params) const {
  const auto it = factories_.find(name);
  if (it == factories_.end()) {
    std::string known;
    for (const std::string& n : Names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("tag detector '" + name + "' unknown; use one of: " + known);
  }
  params.Validate();
  return it->second(params);
}

}  // namespace aperture::perception
