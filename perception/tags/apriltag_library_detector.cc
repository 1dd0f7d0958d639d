#include "perception/tags/apriltag_library_detector.h"

#include <apriltag/apriltag.h>

#include <algorithm>
#include <stdexcept>

namespace aperture::perception {

// The library's pixel centres sit at half-integer coordinates (see the header).
constexpr double kLibraryPixelOffset = 0.5;

AprilTagLibraryDetector::AprilTagLibraryDetector(const TagDetectorParams& params)
    : params_(params) {
  params_.Validate();
  detector_ = apriltag_detector_create();
  for (const std::string& family : params_.families) {
    families_.push_back(CreateAprilTagFamily(family));
    // The quick-decode table holds every code with up to `bits` flipped: for the big families
    // (41 bits and more) 2 bits means millions of entries (49h12: ~80 M, minutes to build), so
    // they correct at most 1 bit (the library's advice).
    const int bits =
        families_.back()->nbits >= 41 ? std::min(params_.max_hamming, 1) : params_.max_hamming;
    apriltag_detector_add_family_bits(detector_, families_.back().get(), bits);
  }
  detector_->quad_decimate = static_cast<float>(params_.quad_decimate);
  detector_->quad_sigma = static_cast<float>(params_.quad_sigma);
  detector_->qtp.min_white_black_diff = params_.min_white_black_diff;
  detector_->nthreads = params_.threads;
  detector_->refine_edges = params_.refine_edges;
  detector_->decode_sharpening = params_.decode_sharpening;
}

AprilTagLibraryDetector::~AprilTagLibraryDetector() {
  if (detector_) apriltag_detector_destroy(detector_);
}

std::vector<TagDetection> AprilTagLibraryDetector::Detect(const cv::Mat& gray) {
  if (gray.type() != CV_8UC1 || gray.empty()) {
    throw std::invalid_argument(
        "AprilTagLibraryDetector: the image must be 8-bit gray (CV_8UC1); "
        "read the source without --color");
  }
  image_u8_t image{gray.cols, gray.rows, static_cast<int32_t>(gray.step[0]),
                   const_cast<uint8_t*>(gray.ptr<uint8_t>())};
  zarray_t* found = apriltag_detector_detect(detector_, &image);
  std::vector<TagDetection> detections;
  detections.reserve(zarray_size(found));
  for (int i = 0; i < zarray_size(found); ++i) {
    apriltag_detection_t* det = nullptr;
    zarray_get(found, i, &det);
    if (det->hamming > params_.max_hamming || det->decision_margin < params_.min_decision_margin) {
      continue;
    }
    TagDetection detection;
    detection.family = det->family->name;
    detection.id = det->id;
    detection.hamming = det->hamming;
    detection.decision_margin = det->decision_margin;
    for (int k = 0; k < 4; ++k) {
      detection.corners_px[k] =
          Eigen::Vector2d(det->p[k][0] - kLibraryPixelOffset, det->p[k][1] - kLibraryPixelOffset);
    }
    detections.push_back(std::move(detection));
  }
  apriltag_detections_destroy(found);
  return detections;
}

std::vector<std::pair<std::string, double>> AprilTagLibraryDetector::LastStageTimes() const {
  std::vector<std::pair<std::string, double>> stages;
  const timeprofile_t* profile = detector_->tp;
  int64_t previous_us = profile->utime;
  for (int i = 0; i < zarray_size(profile->stamps); ++i) {
    timeprofile_entry* entry = nullptr;
    zarray_get_volatile(profile->stamps, i, &entry);
    stages.emplace_back(entry->name, 1e-6 * static_cast<double>(entry->utime - previous_us));
    previous_us = entry->utime;
  }
  return stages;
}

}  // namespace aperture::perception
