#include "perception/gap/gap_node.h"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "control/so3.h"
#include "perception/gap/gap_detector_params_io.h"
#include "perception/sensor_data.h"

namespace aperture::perception {

std::unique_ptr<Node> GapNode::Create(config::ParamReader& params, const FrontEndResources& resources) {
  const CameraCalibration& calibration = resources.RequireCalibration(kName);
  GapDetectorParams detector_params;
  LoadParams(params, &detector_params);
  return std::make_unique<GapNode>(detector_params, calibration.camera);
}

std::vector<SlotSpec> GapNode::Inputs() const { return {MakeSlot<Frame>(kFrameSlot)}; }

std::vector<SlotSpec> GapNode::Outputs() const { return {MakeSlot<GapDetection>(kOutputSlot)}; }

void GapNode::Run(NodeContext& context) {
  context.Set(kOutputSlot, detector_.Detect(context.Get<Frame>(kFrameSlot).image));
}

std::map<std::string, double> GapNode::Metrics(const NodeContext& context) const {
  const auto& d = context.Get<GapDetection>(kOutputSlot);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  return {{"detected", d.detected() ? 1.0 : 0.0},
          {"reprojection_rms_px", d.detected() ? d.corner_rms_px : kNaN},
          {"edge_rms_px", d.detected() ? d.edge_rms_px : kNaN},
          {"distance_m", d.detected() ? d.T_CG.translation().norm() : kNaN}};
}

std::vector<PoseObservation> GapNode::Poses(const NodeContext& context) const {
  const auto& d = context.Get<GapDetection>(kOutputSlot);
  if (!d.detected()) return {};
  PoseObservation observation;
  observation.stream = kName;
  observation.target_frame = "G";
  observation.fixed = PoseObservation::Fixed::kTarget;
  observation.t_s = context.Get<Frame>(kFrameSlot).t_s;
  observation.T_CX = d.T_CG;
  observation.covariance_CX = d.covariance;
  return {observation};
}

void GapNode::DrawOverlay(const NodeContext& context, cv::Mat& bgr) const {
  const auto& d = context.Get<GapDetection>(kOutputSlot);
  if (!d.detected()) return;
  const CameraModel& camera = detector_.camera();
  // Axes as polylines of projected points so they bend like the lens does.
  constexpr double kAxisLength = 0.3;  // [m]
  constexpr int kSteps = 12;
  const cv::Scalar colors[3] = {cv::Scalar(0, 0, 255), cv::Scalar(0, 255, 0), cv::Scalar(255, 0, 0)};
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<cv::Point> line;
    for (int i = 0; i <= kSteps; ++i) {
      Eigen::Vector2d px;
      const Eigen::Vector3d p_G = Eigen::Vector3d::Unit(axis) * kAxisLength * i / kSteps;
      if (!camera.Project(d.T_CG * p_G, &px)) break;
      line.emplace_back(static_cast<int>(std::lround(px.x())), static_cast<int>(std::lround(px.y())));
    }
    if (line.size() > 1) cv::polylines(bgr, line, false, colors[axis], 2, cv::LINE_AA);
  }
  for (size_t i = 0; i < d.corners_px.size(); ++i) {
    const cv::Point c(static_cast<int>(std::lround(d.corners_px[i].x())),
                      static_cast<int>(std::lround(d.corners_px[i].y())));
    cv::circle(bgr, c, 4, i < 4 ? cv::Scalar(0, 255, 255) : cv::Scalar(255, 0, 255), 1, cv::LINE_AA);
  }
}

}  // namespace aperture::perception
