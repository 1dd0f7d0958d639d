#pragma once
// TagDetector on the apriltag library (Olson, ICRA 2011; Wang & Olson, IROS 2016): one library
// detector holding every configured family, run on the distorted 8-bit image.
//
// Corners are reported in OpenCV pixel coordinates (centre of the top-left pixel at (0, 0)); the
// library's own coordinates put that centre at (0.5, 0.5) (checked against rendered corners in
// tests/perception/apriltag_library_detector_test.cc).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "perception/tags/apriltag_family.h"
#include "perception/tags/tag_detector.h"

struct apriltag_detector;

namespace aperture::perception {

class AprilTagLibraryDetector final : public TagDetector {
 public:
  static constexpr const char* kName = "apriltag";

  // std::invalid_argument for invalid params (TagDetectorParams::Validate).
  explicit AprilTagLibraryDetector(const TagDetectorParams& params);
  ~AprilTagLibraryDetector() override;
  AprilTagLibraryDetector(const AprilTagLibraryDetector&) = delete;
  AprilTagLibraryDetector& operator=(const AprilTagLibraryDetector&) = delete;

  std::string Name() const override { return kName; }
  std::vector<TagDetection> Detect(const cv::Mat& gray) override;

  // The library's own profile of the last Detect (its timeprofile stamps: "decimate",
  // "threshold", "unionfind", "fit quads to clusters", "decode+refinement", ...): each stage's
  // name and wall time [s] in the library's order; empty before the first Detect.
  std::vector<std::pair<std::string, double>> LastStageTimes() const;

 private:
  TagDetectorParams params_;
  std::vector<AprilTagFamilyPtr> families_;  // outlive detector_, which points into them
  apriltag_detector* detector_ = nullptr;
};

}  // namespace aperture::perception
