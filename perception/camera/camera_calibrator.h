#pragma once
// Intrinsic calibration from images of a planar target (Zhang's method through OpenCV):
// chessboard (cv::findChessboardCorners + cv::cornerSubPix) or symmetric circle grid
// (cv::findCirclesGrid), solved with cv::calibrateCamera (radtan model) or cv::fisheye::calibrate
// (equidistant model). Reprojection errors are recomputed with our own camera model, so a
// successful result certifies the returned CameraModel, not only OpenCV's internal one.
#include <Eigen/Core>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "perception/camera/camera_model.h"

namespace aperture::perception {

struct PatternSpec {
  enum class Kind { kChessboard, kCircles };
  Kind kind = Kind::kChessboard;
  int cols = 9;              // inner corners per row (chessboard) or circles per row (grid)
  int rows = 6;              // inner corners per column or circles per column
  double spacing_m = 0.025;  // square side or circle centre distance [m]
};

// "chessboard:COLSxROWS:SPACING_M" or "circles:COLSxROWS:SPACING_M", e.g. "chessboard:9x6:0.025".
// Throws std::invalid_argument naming the spec and the bad part.
PatternSpec ParsePatternSpec(const std::string& spec);

enum class CalibrationModel {
  kRadTan,   // RadTanCamera, cv::calibrateCamera
  kFisheye,  // EquidistantCamera, cv::fisheye::calibrate
};

// "radtan" | "fisheye" (alias "equidistant"); throws std::invalid_argument otherwise.
CalibrationModel ParseCalibrationModel(const std::string& name);

struct CalibrationImage {
  std::string name;  // file name, used in results and errors
  cv::Mat image;     // CV_8UC1 or CV_8UC3 (BGR); all images must have the same size
};

struct CalibratorOptions {
  // Fewer views do not constrain focal length, principal point and distortion together.
  int min_images = 3;
  // Estimate k3 of the radtan model. Off by default: k3 is poorly constrained unless the target
  // reaches the image corners, and an unconstrained k3 extrapolates badly outside the target.
  bool radtan_estimate_k3 = false;
};

struct ImageCalibrationResult {
  std::string name;
  bool found = false;   // target detected (only these images are used)
  double rms_px = 0.0;  // reprojection RMS of this image's points with the final model
};

struct CameraCalibrationResult {
  enum class Status { kOk, kTooFewImages, kSolverFailed };
  Status status = Status::kTooFewImages;
  std::string message;                        // why status is not kOk
  std::shared_ptr<const CameraModel> camera;  // set when status == kOk
  double rms_px = 0.0;                        // RMS over all points of |reprojection error| [px]
  int images_used = 0;
  std::vector<ImageCalibrationResult> per_image;  // one per input image, in input order
};

std::ostream& operator<<(std::ostream& os, const CameraCalibrationResult& result);

// Pattern feature points in the order of PatternObjectPoints, or std::nullopt when the full
// pattern is not found. image: CV_8UC1 or CV_8UC3.
std::optional<std::vector<Eigen::Vector2d>> DetectCalibrationPattern(const cv::Mat& image,
                                                                     const PatternSpec& pattern);

// Target points in the target frame (z = 0 plane) [m], row by row.
std::vector<Eigen::Vector3d> PatternObjectPoints(const PatternSpec& pattern);

// Throws std::invalid_argument for an empty image list, an empty/unsupported image or images of
// different sizes (naming the image). Too few detections or a solver failure are reported in
// the result status.
CameraCalibrationResult CalibrateFromImages(const std::vector<CalibrationImage>& images,
                                            const PatternSpec& pattern, CalibrationModel model,
                                            const CalibratorOptions& options = {});

}  // namespace aperture::perception
