#pragma once
// Patterned-gap detector, Falanga et al. 2017 (seed 000), Sec. III-A: Canny edges -> contours
// (Suzuki-Abe, cv::findContours) -> quadrangles -> nested-quadrangle check with area ratio ->
// sub-pixel corners by line intersection -> PnP on the 8 corners -> reprojection check ->
// refinement on all sampled edge points -> region of interest around the last detection (full
// search only when the ROI finds nothing).
//
// The pattern: perception/gap/gap_pattern.h (white surround | black band | white band | opening).
// The outer quadrangle is the white->black boundary, the inner one the black->white boundary,
// so both are edges of the pattern itself whatever is seen through the opening.
//
// Gap frame G: origin at the centre of the opening, x_G along the long side, y_G along the short
// side, z_G the plane normal (x_G, y_G, z_G right-handed). Looking along +z_G, x_G points right
// and y_G down (like an image; sim::Rectangle's object frame). The pattern is symmetric under
// 180 deg rotations about x_G, y_G and z_G; the detector reports the one of these four poses with
// the camera on the -z_G side (z_G points away from the camera) and x_G pointing to the image's
// right half-plane (R_CG(0, 0) >= 0).
//
// Works with every CameraModel (incl. a 180 deg fisheye): edges are handled as bearings
// (CameraModel::Unproject), lines are great circles, and PnP runs on gnomonic coordinates of a
// virtual camera looking at the pattern.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <utility>
#include <vector>

#include "perception/camera/camera_model.h"
#include "perception/gap/gap_pattern.h"

namespace aperture::perception {

// The pattern geometry (opening_size_m, inner_size_m, outer_size_m) is the GapPattern base, shared
// with the simulator's scene; the members below tune the detector.
struct GapDetectorParams : GapPattern {
  double canny_low = 40.0;   // Canny hysteresis thresholds on the 8-bit image
  double canny_high = 120.0;
  double min_perimeter_px = 60.0;  // smaller contours are not looked at
  // cv::approxPolyDP tolerance as a fraction of the contour perimeter. A convex contour that
  // gives more than four vertices is approximated again with the tolerance grown 1.6 x at a time
  // up to approx_epsilon_max_ratio: a far pattern's 2 px white band merges the inner edge with
  // the opening's in the dilated edge map and cuts its corners, so the inner quadrangle comes
  // out with five or six vertices at the tight tolerance.
  double approx_epsilon_ratio = 0.03;
  double approx_epsilon_max_ratio = 0.08;
  double min_side_px = 6.0;  // shortest quadrangle side
  // Accepted outer/inner area ratio: expected (from the sizes) times / divided by this factor;
  // perspective changes the ratio, the PnP reprojection check is the final arbiter.
  double area_ratio_tolerance = 1.4;
  double min_contrast = 20.0;  // gray levels between the two sides of each pattern edge

  int edge_search_px = 3;         // half length of the search along each edge normal [px]
  double edge_sample_step_px = 2.0;  // spacing of edge samples along each side [px]
  int max_samples_per_side = 80;
  double corner_exclusion = 0.12;  // fraction of each side left out at both ends (corners)

  double max_corner_rms_px = 1.5;  // reprojection check after PnP (8 corners) [px]
  double pixel_sigma_px = 0.3;     // edge point noise for the covariance [px]
  int refinement_iterations = 8;

  bool use_roi = true;
  // ROI = bounding box of the last detection's projected outer corners, grown by this fraction
  // of its size on each side plus roi_margin_px.
  double roi_margin_ratio = 0.25;
  int roi_margin_px = 16;
};

// Throws std::invalid_argument naming the field when sizes are not nested (opening < inner <
// outer in both directions), thresholds are not positive or the ratios out of range.
void ValidateGapDetectorParams(const GapDetectorParams& params);

enum class GapDetectionStatus {
  kDetected,
  kNoCandidate,          // no nested quadrangle pair passed the geometric checks
  kReprojectionRejected  // candidates found, but none passed the PnP reprojection check
};
std::string GapDetectionStatusName(GapDetectionStatus status);
// Every status with its name, e.g. for reading a status back from JSON.
const std::vector<std::pair<std::string, GapDetectionStatus>>& GapDetectionStatusNames();

struct GapDetection {
  GapDetectionStatus status = GapDetectionStatus::kNoCandidate;
  bool detected() const { return status == GapDetectionStatus::kDetected; }

  Eigen::Isometry3d T_CG = Eigen::Isometry3d::Identity();  // gap in the camera frame
  // Covariance of [p_CG [m]; rotation [rad]] with the perturbation T_CG = Exp(delta) * T_CG
  // (translation and rotation in C), from the Gauss-Newton normal equations with
  // pixel_sigma_px per edge sample.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  double corner_rms_px = 0.0;  // reprojection RMS of the 8 corners after refinement
  double edge_rms_px = 0.0;    // RMS of the edge samples' distances to the projected edges
  int edge_samples = 0;
  // Sub-pixel corners: outer then inner, each in G order (-x,-y), (+x,-y), (+x,+y), (-x,+y).
  std::vector<Eigen::Vector2d> corners_px;
  bool from_roi = false;  // found in the ROI around the last detection
};

// The pattern's symmetry resolved by a prediction: of T_CG and T_CG turned by 180 deg about z_G
// (the two labellings the detector chooses between by the image, R_CG(0, 0) >= 0), the one whose
// rotation is nearer R_CG_expected. The image convention flips where x_G crosses the image's
// vertical — a gap rolled 45 deg seen from a vehicle banked 45 deg by a gust — so a mission
// flying through a fixed gap picks the labelling by its estimate instead. The translation and a
// covariance in C (GapDetection::covariance) are the same for both.
Eigen::Isometry3d NearestGapLabelling(const Eigen::Isometry3d& T_CG,
                                      const Eigen::Matrix3d& R_CG_expected);

class GapDetector {
 public:
  // Throws std::invalid_argument (ValidateGapDetectorParams).
  GapDetector(const GapDetectorParams& params, std::shared_ptr<const CameraModel> camera);
  ~GapDetector();

  // image: CV_8UC1 or CV_8UC3 of the camera's size (else std::invalid_argument naming the size).
  // Searches the ROI around the previous detection first (when use_roi), then the whole image.
  GapDetection Detect(const cv::Mat& image);
  // Full-image search, ignoring and not updating the tracking state.
  GapDetection DetectFullImage(const cv::Mat& image);
  void ResetTracking() { has_last_ = false; }

  const GapDetectorParams& params() const { return params_; }
  const CameraModel& camera() const { return *camera_; }
  // Pattern corners in G: outer then inner, order as in GapDetection::corners_px.
  std::vector<Eigen::Vector3d> ModelCorners() const;

 private:
  struct Impl;
  // The image as CV_8UC1 (converted into a reused buffer); throws on a wrong size or type.
  const cv::Mat& ToGray(const cv::Mat& image);
  GapDetection DetectIn(const cv::Mat& gray, const cv::Rect& roi);

  GapDetectorParams params_;
  std::shared_ptr<const CameraModel> camera_;
  std::unique_ptr<Impl> impl_;
  bool has_last_ = false;
  Eigen::Isometry3d last_T_CG_ = Eigen::Isometry3d::Identity();
};

}  // namespace aperture::perception
