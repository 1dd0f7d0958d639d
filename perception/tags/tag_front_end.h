#pragma once
// The tag front end on one image: detection on the distorted image (TagDetector), per-tag pose
// with both planar-ambiguity solutions and covariance (EstimateTagPose), flip resolution over
// time and across tags (TagFlipResolver). Used by the `apriltag` node, its bench and benchmark.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "perception/camera/camera_model.h"
#include "perception/tags/tag_detector.h"
#include "perception/tags/tag_flip_resolver.h"
#include "perception/tags/tag_map.h"
#include "perception/tags/tag_pose_estimator.h"

namespace aperture::perception {

struct TagFrontEndParams {
  std::string detector = "apriltag";  // TagDetectorRegistry name
  TagDetectorParams detection;
  // Edge of the black border [m] of every tag (apriltag.size_m) unless `sizes` names the id.
  // 0 = not set: the front end refuses to start (a guessed size scales every pose).
  double size_m = 0.0;
  std::map<int, double> sizes;  // id -> edge [m] (apriltag.sizes: {7: 0.1})
  TagPoseParams pose;
  TagFlipResolverParams flip;

  // std::invalid_argument naming the key: no size, a non-positive size, or bad nested params.
  void Validate() const;
  double SizeOf(int id) const;
};

struct TagResult {
  TagDetection detection;
  double size_m = 0.0;
  std::optional<TagPose> pose;  // empty: pose estimation failed (see EstimateTagPose)
  FlipChoice choice;
  // The chosen candidate (meaningful when pose is set).
  const TagPoseCandidate& chosen() const {
    return choice.use_alternative ? *pose->alternative : pose->best;
  }
};

struct TagFrameResult {
  std::vector<TagResult> tags;
};

// The tags of a frame that have a pose, as tag map observations (the chosen candidate).
std::vector<TagMapObservation> MapObservations(const TagFrameResult& result);

class TagFrontEnd {
 public:
  // std::invalid_argument for invalid params or a missing camera/detector.
  TagFrontEnd(std::unique_ptr<TagDetector> detector, std::shared_ptr<const CameraModel> camera,
              const TagFrontEndParams& params);

  // gray: CV_8UC1 of the camera's size; t_s non-decreasing (the flip resolver's clock).
  TagFrameResult Process(const cv::Mat& gray, double t_s);

  const CameraModel& camera() const { return *camera_; }
  const TagFrontEndParams& params() const { return params_; }
  const TagDetector& detector() const { return *detector_; }

 private:
  std::unique_ptr<TagDetector> detector_;
  std::shared_ptr<const CameraModel> camera_;
  TagFrontEndParams params_;
  TagFlipResolver resolver_;
};

}  // namespace aperture::perception
