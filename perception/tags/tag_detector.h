#pragma once
// The tag detector interface of the `apriltag` front end, so detectors from different libraries
// (the apriltag library here, ViSP's vpDetectorAprilTag in servo/) are selectable and benchmarked
// side by side. A detector finds tags on the image as the camera delivers it (distorted); pose
// estimation (TagPoseEstimator) undistorts the corners through the calibration's camera model.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace aperture::perception {

// One decoded tag on one image.
struct TagDetection {
  std::string family;  // library name (apriltag_family.h), e.g. "tag36h11"
  int id = -1;
  // The four corners of the black border in distorted pixels, in the apriltag library's order:
  // in the tag frame T (x right, y down, z into the tag seen from the front, edge s) they are
  // (-s/2, s/2), (s/2, s/2), (s/2, -s/2), (-s/2, -s/2) (counter-clockwise in the image).
  std::array<Eigen::Vector2d, 4> corners_px;
  double decision_margin = 0.0;  // the library's decoding quality (higher is better)
  int hamming = 0;               // bits corrected while decoding
};

// Detector settings shared by every implementation (each maps them to its library; a setting a
// library lacks is documented by the implementation).
struct TagDetectorParams {
  std::vector<std::string> families{"tag36h11"};  // library or short names; paper D: 36h11
  // Quad detection on an image decimated by this factor; refine_edges restores sub-pixel
  // corners. 2 keeps 12 tags at 640 x 480 within ~3 ms on one core (docs/results/tags.md).
  double quad_decimate = 2.0;
  double quad_sigma = 0.0;  // Gaussian blur [px] before quad detection (0: none)
  // Local contrast [gray levels] below which the library's adaptive threshold leaves a tile
  // unsegmented (its qtp.min_white_black_diff, default 5). With sensor noise of a few levels
  // every flat region passes 5, and the library fits quads to the noise clusters: on the
  // benchmark frame (tests/bench/apriltag_bench.cc, noise sigma ~2-3 levels) that was ~85 % of the
  // detection time; 20 (~7 sigma) still segments every tag border (docs/results/tags.md).
  int min_white_black_diff = 20;
  int threads = 1;  // the front end runs on one core next to the others
  bool refine_edges = true;
  double decode_sharpening = 0.25;  // the library's default
  // Bits corrected at most (the library's default; 36h11 has distance 11). Families of 41 bits
  // and more correct at most 1 (AprilTagLibraryDetector).
  int max_hamming = 2;
  double min_decision_margin = 0.0;  // weaker decodings are dropped (0: keep all)

  // std::invalid_argument naming the field: no family or an unknown one, quad_decimate < 1,
  // quad_sigma < 0, threads < 1, max_hamming outside [0, 3], negative margins.
  void Validate() const;
};

class TagDetector {
 public:
  virtual ~TagDetector() = default;
  virtual std::string Name() const = 0;
  // gray: CV_8UC1 (std::invalid_argument otherwise). Every decoded tag of every configured
  // family that passes max_hamming and min_decision_margin.
  virtual std::vector<TagDetection> Detect(const cv::Mat& gray) = 0;
};

using TagDetectorFactory = std::function<std::unique_ptr<TagDetector>(const TagDetectorParams&)>;

}  // namespace aperture::perception
