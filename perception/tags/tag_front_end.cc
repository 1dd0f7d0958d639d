#include "perception/tags/tag_front_end.h"

#include <cmath>
#include <stdexcept>

namespace aperture::perception {

void TagFrontEndParams::Validate() const {
  detection.Validate();
  if (!(size_m > 0.0) && sizes.empty()) {
    throw std::invalid_argument(
        "apriltag: no tag size; set apriltag.size_m (edge of the black border [m]) and/or "
        "apriltag.sizes ({id: size_m})");
  }
  if (size_m < 0.0 || !std::isfinite(size_m)) {
    throw std::invalid_argument("apriltag.size_m = " + std::to_string(size_m) + " must be > 0");
  }
  for (const auto& [id, size] : sizes) {
    if (!(size > 0.0) || !std::isfinite(size)) {
      throw std::invalid_argument("apriltag.sizes." + std::to_string(id) + " = " +
                                  std::to_string(size) + " must be > 0");
    }
  }
  if (!(pose.refiner.detection_sigma_px > 0.0)) {
    throw std::invalid_argument("apriltag.corner_sigma_px must be > 0");
  }
}

double TagFrontEndParams::SizeOf(int id) const {
  const auto it = sizes.find(id);
  return it != sizes.end() ? it->second : size_m;
}

TagFrontEnd::TagFrontEnd(std::unique_ptr<TagDetector> detector,
                         std::shared_ptr<const CameraModel> camera, const TagFrontEndParams& params)
    : detector_(std::move(detector)),
      camera_(std::move(camera)),
      params_(params),
      resolver_(params.flip) {
  params_.Validate();
  if (!detector_ || !camera_)
    throw std::invalid_argument("TagFrontEnd: detector and camera needed");
}

TagFrameResult TagFrontEnd::Process(const cv::Mat& gray, double t_s) {
  if (gray.cols != camera_->width() || gray.rows != camera_->height()) {
    throw std::invalid_argument("apriltag: image " + std::to_string(gray.cols) + "x" +
                                std::to_string(gray.rows) + " does not match the calibration's " +
                                std::to_string(camera_->width()) + "x" +
                                std::to_string(camera_->height()));
  }
  TagFrameResult result;
  std::vector<TagPoseInImage> posed;
  std::vector<std::size_t> posed_index;
  for (TagDetection& detection : detector_->Detect(gray)) {
    TagResult tag;
    tag.size_m = params_.SizeOf(detection.id);
    // A tag of unknown size (size_m unset and the id not in `sizes`) is reported without pose.
    if (tag.size_m > 0.0) {
      tag.pose = EstimateTagPose(*camera_, detection.corners_px, tag.size_m, params_.pose);
    }
    tag.detection = std::move(detection);
    if (tag.pose) {
      posed.push_back({tag.detection.family, tag.detection.id, *tag.pose});
      posed_index.push_back(result.tags.size());
    }
    result.tags.push_back(std::move(tag));
  }
  const std::vector<FlipChoice> choices = resolver_.Resolve(t_s, posed);
  for (std::size_t k = 0; k < choices.size(); ++k) result.tags[posed_index[k]].choice = choices[k];
  return result;
}

std::vector<TagMapObservation> MapObservations(const TagFrameResult& result) {
  std::vector<TagMapObservation> observations;
  for (const TagResult& tag : result.tags) {
    if (!tag.pose) continue;
    observations.push_back({tag.detection.family, tag.detection.id, tag.size_m, tag.chosen().T_CT,
                            tag.chosen().covariance});
  }
  return observations;
}

}  // namespace aperture::perception
