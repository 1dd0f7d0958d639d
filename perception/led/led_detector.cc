#include "perception/led/led_detector.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "control/require.h"

namespace aperture::perception {
namespace {

// Merges overlapping rectangles until none overlap (few ROIs: quadratic is fine).
std::vector<cv::Rect> MergeOverlapping(std::vector<cv::Rect> rects) {
  bool merged = true;
  while (merged) {
    merged = false;
    for (std::size_t i = 0; i < rects.size() && !merged; ++i) {
      for (std::size_t j = i + 1; j < rects.size() && !merged; ++j) {
        if ((rects[i] & rects[j]).area() > 0) {
          rects[i] |= rects[j];
          rects.erase(rects.begin() + static_cast<std::ptrdiff_t>(j));
          merged = true;
        }
      }
    }
  }
  return rects;
}

}  // namespace

LedDetector::LedDetector(const LedDetectorParams& params) : params_(params) {
  control::RequireInRange(params.threshold, 1, 254, "LedDetectorParams.threshold");
  control::Require(params.smoothing_sigma_px >= 0.0, "LedDetectorParams.smoothing_sigma_px",
                   "must be >= 0");
  control::Require(params.min_area_px >= 1, "LedDetectorParams.min_area_px", "must be >= 1");
  control::Require(params.max_area_px >= params.min_area_px, "LedDetectorParams.max_area_px",
                   "must be >= min_area_px");
  control::Require(params.max_blobs >= 3, "LedDetectorParams.max_blobs",
                   "must be >= 3 (P3P needs three detections)");
  control::Require(params.centroid_floor >= 0 && params.centroid_floor < params.threshold,
                   "LedDetectorParams.centroid_floor", "must be in [0, threshold)");
  control::Require(params.centroid_margin_px >= 0, "LedDetectorParams.centroid_margin_px",
                   "must be >= 0");
}

LedDetectionResult LedDetector::Detect(const cv::Mat& image, const CameraModel& camera,
                                       const std::vector<cv::Rect>& rois) {
  if (image.empty()) throw std::invalid_argument("LedDetector::Detect: empty image");
  if (image.cols != camera.width() || image.rows != camera.height()) {
    throw std::invalid_argument("LedDetector::Detect: image is " + std::to_string(image.cols) +
                                "x" + std::to_string(image.rows) + " but the camera model is " +
                                std::to_string(camera.width()) + "x" +
                                std::to_string(camera.height()) + "; check the calibration");
  }
  if (image.channels() == 3) {
    cv::cvtColor(image, gray_, cv::COLOR_BGR2GRAY);
  } else {
    gray_ = image;
  }
  const cv::Rect full(0, 0, image.cols, image.rows);
  std::vector<cv::Rect> regions;
  for (const cv::Rect& roi : rois) {
    const cv::Rect clipped = roi & full;
    if (clipped.area() > 0) regions.push_back(clipped);
  }
  regions = rois.empty() ? std::vector<cv::Rect>{full} : MergeOverlapping(regions);

  LedDetectionResult result;
  for (const cv::Rect& region : regions) DetectInRegion(gray_, region, camera, &result.detections);
  result.blobs_found = static_cast<int>(result.detections.size());
  if (result.blobs_found > params_.max_blobs) {
    std::partial_sort(result.detections.begin(), result.detections.begin() + params_.max_blobs,
                      result.detections.end(),
                      [](const LedDetection& a, const LedDetection& b) { return a.mass > b.mass; });
    result.detections.resize(params_.max_blobs);
    result.capped = true;
    result.warning = "LED detector: " + std::to_string(result.blobs_found) +
                     " bright blobs, kept the " + std::to_string(params_.max_blobs) +
                     " brightest (max_blobs); reduce exposure or raise the threshold";
  }
  return result;
}

void LedDetector::DetectInRegion(const cv::Mat& gray, const cv::Rect& region,
                                 const CameraModel& camera,
                                 std::vector<LedDetection>* detections) {
  // (C.1): keep pixels above the threshold, zero elsewhere.
  cv::threshold(gray(region), thresholded_, params_.threshold, 0, cv::THRESH_TOZERO);
  if (cv::countNonZero(thresholded_) == 0) return;
  if (params_.smoothing_sigma_px > 0.0) {
    cv::GaussianBlur(thresholded_, smoothed_, cv::Size(0, 0), params_.smoothing_sigma_px);
  } else {
    smoothed_ = thresholded_;
  }
  // Blobs = connected pixels of the smoothed (C.1) image above half the threshold: isolated
  // bright pixels fall below it, the blob edge stays.
  cv::compare(smoothed_, params_.threshold / 2, mask_, cv::CMP_GE);
  const int count = cv::connectedComponentsWithStats(mask_, labels_, stats_, centroids_, 8, CV_32S);
  kept_labels_.clear();
  for (int label = 1; label < count; ++label) {
    const int area = stats_.at<int>(label, cv::CC_STAT_AREA);
    const int w = stats_.at<int>(label, cv::CC_STAT_WIDTH);
    const int h = stats_.at<int>(label, cv::CC_STAT_HEIGHT);
    if (area < params_.min_area_px || area > params_.max_area_px) continue;
    if (static_cast<double>(area) / (w * h) < params_.min_fill_ratio) continue;
    if (std::max(w, h) >= 4 &&
        static_cast<double>(std::max(w, h)) / std::min(w, h) > params_.max_aspect_ratio) {
      continue;
    }
    kept_labels_.push_back(label);
  }
  const cv::Mat patch = gray(region);
  const cv::Rect patch_rect(0, 0, patch.cols, patch.rows);
  for (const int label : kept_labels_) {
    const int m = params_.centroid_margin_px;
    const cv::Rect window =
        cv::Rect(stats_.at<int>(label, cv::CC_STAT_LEFT) - m,
                 stats_.at<int>(label, cv::CC_STAT_TOP) - m,
                 stats_.at<int>(label, cv::CC_STAT_WIDTH) + 2 * m,
                 stats_.at<int>(label, cv::CC_STAT_HEIGHT) + 2 * m) &
        patch_rect;
    // First moments (C.2) M00, M10, M01 in region coordinates.
    double m00 = 0.0, m10 = 0.0, m01 = 0.0;
    for (int y = window.y; y < window.y + window.height; ++y) {
      const int* label_row = labels_.ptr<int>(y);
      const std::uint8_t* value_row = patch.ptr<std::uint8_t>(y);
      for (int x = window.x; x < window.x + window.width; ++x) {
        if (label_row[x] != 0 && label_row[x] != label) continue;
        const double v = static_cast<double>(value_row[x]) - params_.centroid_floor;
        if (v <= 0.0) continue;
        m00 += v;
        m10 += v * x;
        m01 += v * y;
      }
    }
    LedDetection detection;
    detection.area_px = stats_.at<int>(label, cv::CC_STAT_AREA);
    detection.mass = m00;
    detection.px = Eigen::Vector2d(region.x + m10 / m00, region.y + m01 / m00);  // (C.3), (C.4)
    detection.f_C = camera.Unproject(detection.px);
    detections->push_back(detection);
  }
}

}  // namespace aperture::perception
