#pragma once
// Infrared-LED blob detection (Faessler thesis (C.1)-(C.4)): threshold the 8-bit image (C.1),
// Gaussian smoothing, grouping of neighbouring pixels into blobs with area and shape filters,
// intensity-weighted centroids from first image moments (C.2)-(C.4) (over the blob and its tails,
// see centroid_floor), then undistortion through the camera model to unit bearings f_C.
//
// Search regions: the whole image, or ROIs (e.g. boxes around predicted LEDs; the tracker falls
// back to the full image on loss). Blobs are counted per call; beyond max_blobs only the
// max_blobs with the largest intensity mass are kept and `capped` is set with a warning, which
// bounds the cost of the correspondence search that follows.
#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "perception/camera/camera_model.h"

namespace aperture::perception {

struct LedDetectorParams {
  int threshold = 120;           // (C.1) gray level; the thesis found 80-180 to work
  double smoothing_sigma_px = 0.8;  // Gaussian smoothing after the threshold; suppresses hot pixels
  int min_area_px = 2;           // smaller blobs are noise
  int max_area_px = 2500;        // larger blobs are lamps / reflections (a 5 cm disc at 0.3 m)
  // Shape filter: blob area over its bounding box area. A disc fills pi/4 = 0.79, a line ~0.
  double min_fill_ratio = 0.3;
  // Shape filter: longer over shorter bounding box side; merged blobs of LEDs far apart or
  // streaks exceed it. Small blobs (< 4 px a side) are exempt: rounding dominates their shape.
  double max_aspect_ratio = 3.0;
  int max_blobs = 10;            // cap on detections per frame (C.5 grows with C(n_D, 3))
  // Centroid moments (C.2) weigh pixels by max(0, I - centroid_floor) over the blob grown by
  // centroid_margin_px (pixels of other blobs excluded) instead of by I' of (C.1): a hard cut at
  // the threshold biases sub-pixel centroids by up to 0.3 px, a low floor keeps the blob tails.
  int centroid_floor = 20;       // gray level; above the dark infrared background
  int centroid_margin_px = 3;
};

struct LedDetection {
  Eigen::Vector2d px = Eigen::Vector2d::Zero();     // distorted centroid (C.3), (C.4) [px]
  Eigen::Vector3d f_C = Eigen::Vector3d::UnitZ();  // unit bearing through px
  double mass = 0.0;                                // M_00 of the smoothed blob (C.2)
  int area_px = 0;
};

struct LedDetectionResult {
  std::vector<LedDetection> detections;
  int blobs_found = 0;   // blobs passing the filters before the cap
  bool capped = false;   // blobs_found > max_blobs; `warning` says so
  std::string warning;
};

class LedDetector {
 public:
  // Throws std::invalid_argument naming the field for threshold outside [1, 254], negative sigma,
  // min_area_px < 1, max_area_px < min_area_px, or max_blobs < 3.
  explicit LedDetector(const LedDetectorParams& params = {});

  // image: CV_8UC1 (CV_8UC3 is converted to gray) of the camera's size. rois: search regions in
  // pixels (clipped to the image; overlapping ROIs are merged into their bounding box); empty =
  // whole image. Throws std::invalid_argument when the image is empty or of another size.
  LedDetectionResult Detect(const cv::Mat& image, const CameraModel& camera,
                            const std::vector<cv::Rect>& rois = {});

  const LedDetectorParams& params() const { return params_; }

 private:
  void DetectInRegion(const cv::Mat& gray, const cv::Rect& region, const CameraModel& camera,
                      std::vector<LedDetection>* detections);

  LedDetectorParams params_;
  // Per-frame buffers reused across calls.
  cv::Mat gray_, thresholded_, smoothed_, mask_, labels_, stats_, centroids_;
  std::vector<int> kept_labels_;
};

}  // namespace aperture::perception
