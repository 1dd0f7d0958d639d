#pragma once
// The LEDs of an infrared-LED target: their positions p_T [m] in the target frame T (Faessler
// thesis, Appendix C). A configuration is only usable when the LEDs' image fixes the pose
// uniquely, so construction validates it:
//  - 4..8 LEDs (fewer give no verification LED for P3P; more make the brute-force correspondence
//    search (C.5) too expensive),
//  - no two LEDs closer than kMinLedSpacing_m (their blobs would merge),
//  - non-coplanar (some LED farther than kCoplanarTolerance_m from the best-fit plane),
//  - non-symmetric: no non-identity permutation of the LEDs is reproduced by a proper rigid motion
//    within kSymmetryTolerance_m (else the correspondences, hence the pose, are ambiguous).
// Violations throw std::invalid_argument naming the source (file) and the reason.
#include <Eigen/Core>
#include <istream>
#include <string>
#include <vector>

namespace aperture::perception {

class LedConfiguration {
 public:
  static constexpr int kMinLeds = 4;
  static constexpr int kMaxLeds = 8;
  static constexpr double kMinLedSpacing_m = 0.01;
  static constexpr double kCoplanarTolerance_m = 0.003;
  // A relabelling reproduced within 1.5 cm moves every reprojection by < 5 px (lambda_r) at 1.3 m
  // with a 420 px focal length: the correspondence search could not tell the labellings apart.
  static constexpr double kSymmetryTolerance_m = 0.015;

  // Validates p_T; `source` (file path or a label) only feeds error messages.
  LedConfiguration(std::vector<Eigen::Vector3d> p_T, std::string source);

  // Reads `leds: [[x, y, z], ...]` (metres, frame T) from a YAML file; other keys are rejected.
  // Unreadable file -> std::runtime_error; malformed or invalid content -> std::invalid_argument.
  static LedConfiguration Load(const std::string& path);
  // Load's parsing of a file's content `yaml`; `source` (the file) names it in errors.
  static LedConfiguration Parse(std::istream& yaml, const std::string& source);

  // A 5-LED target with circumsphere radius ~11 cm (size of the thesis' targets, Fig. C.2).
  static LedConfiguration Default();

  const std::vector<Eigen::Vector3d>& p_T() const { return p_T_; }
  int size() const { return static_cast<int>(p_T_.size()); }
  const std::string& source() const { return source_; }

 private:
  std::vector<Eigen::Vector3d> p_T_;
  std::string source_;
};

}  // namespace aperture::perception
