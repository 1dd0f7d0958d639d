#include "perception/camera/camera_calibrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "config/usage_error.h"
#include "perception/camera/camera_factory.h"

namespace aperture::perception {
namespace {

[[noreturn]] void FailSpec(const std::string& spec, const std::string& problem) {
  throw config::UsageError("--pattern '" + spec + "': " + problem +
                           "; expected KIND:COLSxROWS:SPACING_M, e.g. chessboard:9x6:0.025 "
                           "or circles:6x6:0.03");
}

cv::Mat Gray8(const cv::Mat& image) {
  if (image.type() == CV_8UC1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

std::vector<cv::Point3f> ToCv(const std::vector<Eigen::Vector3d>& points) {
  std::vector<cv::Point3f> out;
  for (const Eigen::Vector3d& p : points) out.emplace_back(p.x(), p.y(), p.z());
  return out;
}

std::vector<cv::Point2f> ToCv(const std::vector<Eigen::Vector2d>& points) {
  std::vector<cv::Point2f> out;
  for (const Eigen::Vector2d& p : points) out.emplace_back(p.x(), p.y());
  return out;
}

// Blob detector for printed dark discs: OpenCV's defaults except the area cap. The default cap of
// 5000 px^2 rejects the discs of a target filling a 640x480 view (radius > 40 px); the grid
// topology check in findCirclesGrid rejects spurious blobs. The default threshold range
// (50..220) is kept: on the ViSP photos a wider range (20..240) raised the RMS from 0.26 to
// 0.32 px because the blob centre averages contours over all thresholds.
cv::Ptr<cv::FeatureDetector> MakeCircleDetector() {
  cv::SimpleBlobDetector::Params params;
  params.maxArea = 1e5f;
  return cv::SimpleBlobDetector::create(params);
}

std::string StatusName(CameraCalibrationResult::Status status) {
  switch (status) {
    case CameraCalibrationResult::Status::kOk:
      return "ok";
    case CameraCalibrationResult::Status::kTooFewImages:
      return "too_few_images";
    case CameraCalibrationResult::Status::kSolverFailed:
      return "solver_failed";
  }
  return "unknown";
}

}  // namespace

PatternSpec ParsePatternSpec(const std::string& spec) {
  const size_t first = spec.find(':');
  const size_t second = first == std::string::npos ? first : spec.find(':', first + 1);
  if (second == std::string::npos) FailSpec(spec, "needs three ':'-separated parts");
  PatternSpec pattern;
  const std::string kind = spec.substr(0, first);
  if (kind == "chessboard") {
    pattern.kind = PatternSpec::Kind::kChessboard;
  } else if (kind == "circles") {
    pattern.kind = PatternSpec::Kind::kCircles;
  } else {
    FailSpec(spec, "unknown kind '" + kind + "' (chessboard or circles)");
  }
  const std::string size = spec.substr(first + 1, second - first - 1);
  const std::string spacing = spec.substr(second + 1);
  {
    std::istringstream in(size);
    char x = 0;
    if (!(in >> pattern.cols >> x >> pattern.rows) || x != 'x' || !in.eof()) {
      FailSpec(spec, "size '" + size + "' is not COLSxROWS");
    }
  }
  if (pattern.cols < 2 || pattern.rows < 2 || pattern.cols * pattern.rows < 6) {
    FailSpec(spec, "size '" + size + "' is too small (at least 2 per side and 6 points)");
  }
  {
    std::istringstream in(spacing);
    if (!(in >> pattern.spacing_m) || !in.eof() || !std::isfinite(pattern.spacing_m) ||
        pattern.spacing_m <= 0.0) {
      FailSpec(spec, "spacing '" + spacing + "' is not a positive number of metres");
    }
  }
  return pattern;
}

CalibrationModel ParseCalibrationModel(const std::string& name) {
  if (name == "radtan") return CalibrationModel::kRadTan;
  if (name == "fisheye" || name == "equidistant") return CalibrationModel::kFisheye;
  throw std::invalid_argument("calibration model '" + name + "' is unknown; use radtan or fisheye");
}

std::vector<Eigen::Vector3d> PatternObjectPoints(const PatternSpec& pattern) {
  std::vector<Eigen::Vector3d> points;
  for (int r = 0; r < pattern.rows; ++r)
    for (int c = 0; c < pattern.cols; ++c)
      points.emplace_back(c * pattern.spacing_m, r * pattern.spacing_m, 0.0);
  return points;
}

std::optional<std::vector<Eigen::Vector2d>> DetectCalibrationPattern(const cv::Mat& image,
                                                                     const PatternSpec& pattern) {
  const cv::Mat gray = Gray8(image);
  const cv::Size size(pattern.cols, pattern.rows);
  std::vector<cv::Point2f> points;
  if (pattern.kind == PatternSpec::Kind::kChessboard) {
    if (!cv::findChessboardCorners(gray, size, points,
                                   cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
      return std::nullopt;
    }
    // Refinement window: up to 11x11 px, but within 40% of the closest corner distance so the
    // window never reaches a neighbouring corner on small or distant boards.
    double min_distance = std::numeric_limits<double>::infinity();
    for (int r = 0; r < pattern.rows; ++r) {
      for (int c = 0; c < pattern.cols; ++c) {
        const cv::Point2f& p = points[r * pattern.cols + c];
        if (c + 1 < pattern.cols)
          min_distance = std::min(min_distance, cv::norm(points[r * pattern.cols + c + 1] - p));
        if (r + 1 < pattern.rows)
          min_distance = std::min(min_distance, cv::norm(points[(r + 1) * pattern.cols + c] - p));
      }
    }
    const int half = std::clamp(static_cast<int>(0.4 * min_distance), 2, 5);
    cv::cornerSubPix(gray, points, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
  } else {
    if (!cv::findCirclesGrid(gray, size, points, cv::CALIB_CB_SYMMETRIC_GRID,
                             MakeCircleDetector())) {
      return std::nullopt;
    }
  }
  std::vector<Eigen::Vector2d> out;
  for (const cv::Point2f& p : points) out.emplace_back(p.x, p.y);
  return out;
}

CameraCalibrationResult CalibrateFromImages(const std::vector<CalibrationImage>& images,
                                            const PatternSpec& pattern, CalibrationModel model,
                                            const CalibratorOptions& options) {
  if (images.empty()) throw std::invalid_argument("CalibrateFromImages: no images given");
  const cv::Size image_size = images.front().image.size();
  for (const CalibrationImage& image : images) {
    if (image.image.empty() || (image.image.type() != CV_8UC1 && image.image.type() != CV_8UC3)) {
      throw std::invalid_argument("calibration image '" + image.name +
                                  "' is empty or not 8-bit gray/BGR; check the file");
    }
    if (image.image.size() != image_size) {
      throw std::invalid_argument(
          "calibration image '" + image.name + "' is " + std::to_string(image.image.cols) + "x" +
          std::to_string(image.image.rows) + " but '" + images.front().name + "' is " +
          std::to_string(image_size.width) + "x" + std::to_string(image_size.height) +
          "; calibrate images of one camera at one resolution");
    }
  }

  CameraCalibrationResult result;
  const std::vector<Eigen::Vector3d> object = PatternObjectPoints(pattern);
  std::vector<std::vector<Eigen::Vector2d>> detections;
  std::vector<size_t> used;  // index into images of every detection
  for (size_t i = 0; i < images.size(); ++i) {
    ImageCalibrationResult per_image;
    per_image.name = images[i].name;
    if (auto points = DetectCalibrationPattern(images[i].image, pattern)) {
      per_image.found = true;
      detections.push_back(std::move(*points));
      used.push_back(i);
    }
    result.per_image.push_back(per_image);
  }
  result.images_used = static_cast<int>(detections.size());
  if (result.images_used < options.min_images) {
    result.status = CameraCalibrationResult::Status::kTooFewImages;
    result.message = "target found in " + std::to_string(result.images_used) + " of " +
                     std::to_string(images.size()) + " images, need " +
                     std::to_string(options.min_images) +
                     "; check the pattern size (cols x rows) and add views";
    return result;
  }

  std::vector<std::vector<cv::Point3f>> object_points(detections.size(), ToCv(object));
  std::vector<std::vector<cv::Point2f>> image_points;
  for (const auto& d : detections) image_points.push_back(ToCv(d));
  cv::Matx33d K;
  cv::Mat distortion;
  std::vector<cv::Mat> rvecs, tvecs;
  try {
    if (model == CalibrationModel::kRadTan) {
      int flags = 0;
      if (!options.radtan_estimate_k3) flags |= cv::CALIB_FIX_K3;
      cv::calibrateCamera(object_points, image_points, image_size, K, distortion, rvecs, tvecs,
                          flags);
    } else {
      // cv::fisheye::calibrate's own initialisation diverges on narrow lenses seen in few views
      // (the 4 ViSP photos: 172 px RMS). Also start it from a distortion-free pinhole fit (0.26
      // px there) and keep the attempt with the lower RMS.
      cv::Mat K_pinhole, d_pinhole;
      std::vector<cv::Mat> r_pinhole, t_pinhole;
      cv::calibrateCamera(
          object_points, image_points, image_size, K_pinhole, d_pinhole, r_pinhole, t_pinhole,
          cv::CALIB_FIX_K1 | cv::CALIB_FIX_K2 | cv::CALIB_FIX_K3 | cv::CALIB_ZERO_TANGENT_DIST);
      double best_rms = std::numeric_limits<double>::infinity();
      for (const bool from_pinhole : {false, true}) {
        cv::Matx33d K_attempt = from_pinhole ? cv::Matx33d(K_pinhole) : cv::Matx33d::eye();
        cv::Vec4d d_attempt(0, 0, 0, 0);
        std::vector<cv::Vec3d> r_attempt, t_attempt;
        int flags = cv::fisheye::CALIB_RECOMPUTE_EXTRINSIC | cv::fisheye::CALIB_FIX_SKEW;
        if (from_pinhole) flags |= cv::fisheye::CALIB_USE_INTRINSIC_GUESS;
        double rms = std::numeric_limits<double>::infinity();
        try {
          rms = cv::fisheye::calibrate(
              object_points, image_points, image_size, K_attempt, d_attempt, r_attempt, t_attempt,
              flags, cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12));
        } catch (const cv::Exception&) {
          continue;  // the other attempt may succeed; both failing is reported below
        }
        if (!(rms < best_rms)) continue;
        best_rms = rms;
        K = K_attempt;
        distortion = cv::Mat(d_attempt).clone();
        rvecs.clear();
        tvecs.clear();
        for (size_t i = 0; i < r_attempt.size(); ++i) {
          rvecs.push_back(cv::Mat(r_attempt[i]).clone());
          tvecs.push_back(cv::Mat(t_attempt[i]).clone());
        }
      }
      if (!std::isfinite(best_rms)) {
        result.status = CameraCalibrationResult::Status::kSolverFailed;
        result.message = "cv::fisheye::calibrate failed from both initialisations";
        return result;
      }
    }
  } catch (const cv::Exception& e) {
    result.status = CameraCalibrationResult::Status::kSolverFailed;
    result.message = "OpenCV calibration failed: " + e.err;
    return result;
  }

  Eigen::VectorXd coefficients(distortion.total());
  for (int i = 0; i < coefficients.size(); ++i) coefficients[i] = distortion.at<double>(i);
  if (model == CalibrationModel::kRadTan && !options.radtan_estimate_k3) {
    coefficients.conservativeResize(4);  // k3 fixed at zero: a 4-coefficient model
  }
  try {
    result.camera = CreateCameraModel(
        model == CalibrationModel::kRadTan ? "radtan" : "equidistant", image_size.width,
        image_size.height, Eigen::Vector4d(K(0, 0), K(1, 1), K(0, 2), K(1, 2)), coefficients);
  } catch (const std::invalid_argument& e) {
    result.status = CameraCalibrationResult::Status::kSolverFailed;
    result.message = std::string("calibration produced an invalid camera: ") + e.what();
    return result;
  }

  // Reprojection errors with our model and OpenCV's target poses.
  double total_squared = 0.0;
  size_t total_points = 0;
  for (size_t v = 0; v < detections.size(); ++v) {
    cv::Matx33d R_cv;
    cv::Rodrigues(rvecs[v], R_cv);
    Eigen::Matrix3d R_CT;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R_CT(r, c) = R_cv(r, c);
    const Eigen::Vector3d p_CT(tvecs[v].at<double>(0), tvecs[v].at<double>(1),
                               tvecs[v].at<double>(2));
    double squared = 0.0;
    for (size_t k = 0; k < object.size(); ++k) {
      Eigen::Vector2d px;
      if (!result.camera->Project(R_CT * object[k] + p_CT, &px)) {
        result.status = CameraCalibrationResult::Status::kSolverFailed;
        result.message = "target point " + std::to_string(k) + " of image '" +
                         images[used[v]].name + "' does not project with the estimated model";
        result.camera.reset();
        return result;
      }
      squared += (px - detections[v][k]).squaredNorm();
    }
    result.per_image[used[v]].rms_px = std::sqrt(squared / object.size());
    total_squared += squared;
    total_points += object.size();
  }
  result.rms_px = std::sqrt(total_squared / total_points);
  result.status = CameraCalibrationResult::Status::kOk;
  return result;
}

std::ostream& operator<<(std::ostream& os, const CameraCalibrationResult& result) {
  os << "calibration " << StatusName(result.status);
  if (!result.message.empty()) os << " (" << result.message << ")";
  os << ": " << result.images_used << "/" << result.per_image.size() << " images used";
  if (result.camera) {
    const Eigen::Vector4d k = result.camera->intrinsics();
    os << ", rms " << result.rms_px << " px, model " << result.camera->model_name() << " fx "
       << k[0] << " fy " << k[1] << " cx " << k[2] << " cy " << k[3] << " distortion ["
       << result.camera->distortion().transpose() << "]";
  }
  for (const ImageCalibrationResult& image : result.per_image) {
    os << "\n  " << image.name << ": "
       << (image.found ? "rms " + std::to_string(image.rms_px) + " px" : std::string("not found"));
  }
  return os;
}

}  // namespace aperture::perception
