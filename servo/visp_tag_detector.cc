#include "servo/visp_tag_detector.h"

#include <visp3/core/vpImage.h>
#include <visp3/detection/vpDetectorAprilTag.h>

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "perception/tags/apriltag_family.h"

namespace aperture::servo {
namespace {

// ViSP's corners use the apriltag library's pixel coordinates (pixel centres at +0.5).
constexpr double kLibraryPixelOffset = 0.5;

vpDetectorAprilTag::vpAprilTagFamily VispFamily(const std::string& family) {
  static const std::pair<const char*, vpDetectorAprilTag::vpAprilTagFamily> kFamilies[] = {
      {"tag36h11", vpDetectorAprilTag::TAG_36h11},
      {"tag25h9", vpDetectorAprilTag::TAG_25h9},
      {"tag16h5", vpDetectorAprilTag::TAG_16h5},
      {"tagCircle21h7", vpDetectorAprilTag::TAG_CIRCLE21h7},
  };
  for (const auto& [name, value] : kFamilies) {
    if (family == name) return value;
  }
  // Debian's ViSP 3.5 declares tagStandard41h12, tagStandard52h13, tagCircle49h12 and
  // tagCustom48h12 but is built with them disabled ("... are disabled" and no detections).
  throw std::invalid_argument("visp tag detector: family '" + family +
                              "' is not available in this ViSP build (tag36h11, tag25h9, "
                              "tag16h5, tagCircle21h7); use apriltag.detector=apriltag");
}

class VispTagDetector final : public perception::TagDetector {
 public:
  explicit VispTagDetector(const perception::TagDetectorParams& params) {
    params.Validate();
    if (params.min_decision_margin > 0.0 || params.max_hamming < 2) {
      throw std::invalid_argument(
          "visp tag detector: ViSP 3.5 reports no decision margin or corrected bits; leave "
          "apriltag.min_decision_margin at 0 and apriltag.max_hamming at 2");
    }
    for (const std::string& name : params.families) {
      const std::string family = perception::CanonicalAprilTagFamilyName(name);
      auto detector = std::make_unique<vpDetectorAprilTag>(VispFamily(family));
      detector->setAprilTagQuadDecimate(static_cast<float>(params.quad_decimate));
      detector->setAprilTagQuadSigma(static_cast<float>(params.quad_sigma));
      detector->setAprilTagNbThreads(params.threads);
      detector->setAprilTagRefineEdges(params.refine_edges);
      detector->setAprilTagDecodeSharpening(params.decode_sharpening);
      detectors_.emplace_back(family, std::move(detector));
    }
  }

  std::string Name() const override { return kVispTagDetectorName; }

  std::vector<perception::TagDetection> Detect(const cv::Mat& gray) override {
    if (gray.type() != CV_8UC1 || gray.empty()) {
      throw std::invalid_argument("visp tag detector: the image must be 8-bit gray (CV_8UC1)");
    }
    image_.resize(gray.rows, gray.cols);
    for (int row = 0; row < gray.rows; ++row) {
      std::memcpy(image_[row], gray.ptr<unsigned char>(row), gray.cols);
    }
    std::vector<perception::TagDetection> detections;
    for (auto& [family, detector] : detectors_) {
      detector->detect(image_);
      const std::vector<int> ids = detector->getTagsId();
      for (std::size_t i = 0; i < detector->getNbObjects(); ++i) {
        const std::vector<vpImagePoint>& polygon = detector->getPolygon(i);
        if (polygon.size() != 4) continue;
        perception::TagDetection detection;
        detection.family = family;
        detection.id = ids[i];
        detection.decision_margin = std::numeric_limits<double>::quiet_NaN();
        for (int k = 0; k < 4; ++k) {
          detection.corners_px[k] = Eigen::Vector2d(polygon[k].get_u() - kLibraryPixelOffset,
                                                    polygon[k].get_v() - kLibraryPixelOffset);
        }
        detections.push_back(std::move(detection));
      }
    }
    return detections;
  }

 private:
  std::vector<std::pair<std::string, std::unique_ptr<vpDetectorAprilTag>>> detectors_;
  vpImage<unsigned char> image_;
};

}  // namespace

std::unique_ptr<perception::TagDetector> CreateVispTagDetector(
    const perception::TagDetectorParams& params) {
  return std::make_unique<VispTagDetector>(params);
}

}  // namespace aperture::servo
