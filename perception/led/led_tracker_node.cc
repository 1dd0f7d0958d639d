#include "perception/led/led_tracker_node.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "control/so3.h"
#include "perception/sensor_data.h"

namespace aperture::perception {

std::unique_ptr<Node> LedTrackerNode::Create(config::ParamReader& params,
                                             const FrontEndResources& resources) {
  const CameraCalibration& calibration = resources.RequireCalibration(kName);
  std::string config_path;
  params.Read("config", &config_path);
  LedTrackerParams tracker_params;
  params.Read("threshold", &tracker_params.detector.threshold);
  params.Read("max_blobs", &tracker_params.detector.max_blobs);
  params.ReadEnum("p3p", &tracker_params.correspondence.p3p_method,
                  {{"kneip", P3pMethod::kKneip},
                   {"opengv", P3pMethod::kOpenGv},
                   {"ap3p", P3pMethod::kAp3p}});
  params.Read("reprojection_threshold_px",
              &tracker_params.correspondence.reprojection_threshold_px);
  params.Read("max_rms_px", &tracker_params.max_rms_px);
  LedConfiguration configuration =
      config_path.empty() ? LedConfiguration::Default() : LedConfiguration::Load(config_path);
  return std::make_unique<LedTrackerNode>(
      LedTracker(std::move(configuration), calibration.camera, tracker_params));
}

std::vector<SlotSpec> LedTrackerNode::Inputs() const { return {MakeSlot<Frame>(kFrameSlot)}; }

std::vector<SlotSpec> LedTrackerNode::Outputs() const {
  return {MakeSlot<LedTrackResult>(kOutputSlot)};
}

void LedTrackerNode::Run(NodeContext& context) {
  const Frame& frame = context.Get<Frame>(kFrameSlot);
  LedTrackResult result = tracker_.Track(frame.image, frame.t_s);
  if (!result.warning.empty()) {
    std::cerr << "frame " << frame.index << ": " << result.warning << "\n";
  }
  context.Set(kOutputSlot, std::move(result));
}

std::map<std::string, double> LedTrackerNode::Metrics(const NodeContext& context) const {
  const auto& result = context.Get<LedTrackResult>(kOutputSlot);
  return {
      {"detections", static_cast<double>(result.detections.size())},
      {"correspondences", static_cast<double>(result.correspondences.size())},
      {"merged_detections", static_cast<double>(result.merged_detections)},
      {"rms_px", result.has_pose() ? result.rms_px : std::numeric_limits<double>::quiet_NaN()},
      {"status", static_cast<double>(result.status)},
      {"blob_cap_hit", result.warning.empty() ? 0.0 : 1.0},
  };
}

std::vector<PoseObservation> LedTrackerNode::Poses(const NodeContext& context) const {
  const auto& result = context.Get<LedTrackResult>(kOutputSlot);
  if (!result.has_pose()) return {};
  PoseObservation observation;
  observation.stream = kPoseStream;
  observation.target_frame = "T";
  observation.fixed = PoseObservation::Fixed::kCamera;
  observation.t_s = context.Get<Frame>(kFrameSlot).t_s;
  observation.T_CX = *result.T_CT;
  // (C.9) perturbs p_CT + dt; the observation's convention perturbs Exp(dr) p_CT + dt', so
  // dt' = dt + [p_CT]x dr.
  Matrix6d B = Matrix6d::Identity();
  B.topRightCorner<3, 3>() = control::Skew(result.T_CT->translation());
  observation.covariance_CX = B * *result.covariance * B.transpose();
  return {observation};
}

void LedTrackerNode::DrawOverlay(const NodeContext& context, cv::Mat& bgr) const {
  const auto& result = context.Get<LedTrackResult>(kOutputSlot);
  const CameraModel& camera = tracker_.camera();
  auto point = [](const Eigen::Vector2d& px) {
    return cv::Point(static_cast<int>(std::lround(px.x())), static_cast<int>(std::lround(px.y())));
  };
  for (const LedDetection& detection : result.detections) {
    cv::circle(bgr, point(detection.px), 6, cv::Scalar(0, 255, 255), 1, cv::LINE_AA);
  }
  if (result.has_pose()) {
    for (const Eigen::Vector3d& p_T : tracker_.configuration().p_T()) {
      Eigen::Vector2d px;
      if (camera.Project(*result.T_CT * p_T, &px)) {
        cv::drawMarker(bgr, point(px), cv::Scalar(0, 255, 0), cv::MARKER_CROSS, 10, 1);
      }
    }
    // Target axes, 5 cm: x red, y green, z blue.
    Eigen::Vector2d origin;
    if (camera.Project(result.T_CT->translation(), &origin)) {
      const cv::Scalar colors[3] = {{0, 0, 255}, {0, 255, 0}, {255, 0, 0}};
      for (int axis = 0; axis < 3; ++axis) {
        Eigen::Vector2d tip;
        if (camera.Project(*result.T_CT * (0.05 * Eigen::Vector3d::Unit(axis)), &tip)) {
          cv::line(bgr, point(origin), point(tip), colors[axis], 2, cv::LINE_AA);
        }
      }
    }
  }
  char text[160];
  if (result.has_pose()) {
    const Eigen::Vector3d p = result.T_CT->translation();
    std::snprintf(text, sizeof(text), "led %s  p_CT [%.3f %.3f %.3f] m  rms %.2f px",
                  LedTrackStatusName(result.status).c_str(), p.x(), p.y(), p.z(), result.rms_px);
  } else {
    std::snprintf(text, sizeof(text), "led %s  (%zu blobs)",
                  LedTrackStatusName(result.status).c_str(), result.detections.size());
  }
  const double scale = std::max(0.35, bgr.cols / 1500.0);
  const cv::Point origin_text(8, bgr.rows - 12);
  cv::putText(bgr, text, origin_text, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 3,
              cv::LINE_AA);
  cv::putText(bgr, text, origin_text, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 255, 0), 1,
              cv::LINE_AA);
}

}  // namespace aperture::perception
