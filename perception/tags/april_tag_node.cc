#include "perception/tags/april_tag_node.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "control/constants.h"
#include "control/so3.h"
#include "perception/sensor_data.h"
#include "perception/tags/tag_front_end_params_io.h"
#include "perception/tags/tag_map_writer.h"

namespace aperture::perception {
namespace {

using control::kNaN;
constexpr const char* kTagsCsv = "tags.csv";
constexpr const char* kMapYaml = "tag_map.yaml";
constexpr const char* kMapPng = "tag_map.png";

std::vector<std::string> TagsCsvColumns() {
  std::vector<std::string> columns{"t_s", "index", "family", "id"};
  for (int k = 0; k < 4; ++k) {
    columns.push_back("u" + std::to_string(k));
    columns.push_back("v" + std::to_string(k));
  }
  for (const char* name : {"tx", "ty", "tz", "qx", "qy", "qz", "qw", "decision_margin",
                           "ambiguity_ratio", "flip_decision", "rms_px"}) {
    columns.emplace_back(name);
  }
  return columns;
}

}  // namespace

AprilTagNode::AprilTagNode(TagFrontEnd front_end, std::optional<TagMapParams> map_params,
                           const std::string& output_directory)
    : front_end_(std::move(front_end)), output_directory_(output_directory) {
  if (map_params) map_ = std::make_unique<TagMap>(*map_params);
  if (!output_directory_.empty()) {
    csv_ = std::make_unique<output::CsvWriter>(
        (std::filesystem::path(output_directory_) / kTagsCsv).string(), TagsCsvColumns());
  }
}

std::unique_ptr<Node> AprilTagNode::Create(config::ParamReader& params,
                                           const FrontEndResources& resources) {
  const CameraCalibration& calibration = resources.RequireCalibration(kName);
  TagFrontEndParams front_end_params;
  LoadParams(params, &front_end_params);
  bool map = false;
  params.Read("map", &map);
  TagMapParams map_params;
  params.ReadSection("mapping", &map_params);
  std::unique_ptr<TagDetector> detector =
      resources.tag_detectors.Create(front_end_params.detector, front_end_params.detection);
  TagFrontEnd front_end(std::move(detector), calibration.camera, front_end_params);
  return std::make_unique<AprilTagNode>(
      std::move(front_end), map ? std::optional<TagMapParams>(map_params) : std::nullopt,
      resources.output_directory);
}

std::vector<SlotSpec> AprilTagNode::Inputs() const { return {MakeSlot<Frame>(kFrameSlot)}; }

std::vector<SlotSpec> AprilTagNode::Outputs() const {
  return {MakeSlot<TagFrameResult>(kOutputSlot)};
}

std::string AprilTagNode::StreamName(const TagDetection& detection) const {
  const std::string tag = "tag" + std::to_string(detection.id);
  return front_end_.params().detection.families.size() == 1 ? tag : detection.family + "_" + tag;
}

void AprilTagNode::Run(NodeContext& context) {
  const Frame& frame = context.Get<Frame>(kFrameSlot);
  TagFrameResult result = front_end_.Process(frame.image, frame.t_s);
  if (map_) map_->AddImage(frame.t_s, MapObservations(result));
  if (csv_) WriteRows(frame, result);
  context.Set(kOutputSlot, std::move(result));
}

void AprilTagNode::WriteRows(const Frame& frame, const TagFrameResult& result) {
  for (const TagResult& tag : result.tags) {
    std::vector<output::CsvCell> cells{frame.t_s, double(frame.index), tag.detection.family,
                                       double(tag.detection.id)};
    for (const Eigen::Vector2d& corner : tag.detection.corners_px) {
      cells.emplace_back(corner.x());
      cells.emplace_back(corner.y());
    }
    if (tag.pose) {
      const Eigen::Isometry3d& T_CT = tag.chosen().T_CT;
      const Eigen::Quaterniond q(T_CT.rotation());
      for (double value : {T_CT.translation().x(), T_CT.translation().y(), T_CT.translation().z(),
                           q.x(), q.y(), q.z(), q.w()}) {
        cells.emplace_back(value);
      }
    } else {
      for (int k = 0; k < 7; ++k) cells.emplace_back(kNaN);
    }
    cells.emplace_back(tag.detection.decision_margin);
    cells.emplace_back(tag.pose ? tag.pose->ambiguity_ratio : kNaN);
    cells.emplace_back(tag.pose ? FlipDecisionName(tag.choice.decision) : std::string("no_pose"));
    cells.emplace_back(tag.pose ? tag.chosen().rms_px : kNaN);
    csv_->WriteCells(cells);
  }
}

std::map<std::string, double> AprilTagNode::Metrics(const NodeContext& context) const {
  const auto& result = context.Get<TagFrameResult>(kOutputSlot);
  double posed = 0, ambiguous = 0, alternatives = 0, rms_sum = 0;
  for (const TagResult& tag : result.tags) {
    if (!tag.pose) continue;
    ++posed;
    rms_sum += tag.chosen().rms_px;
    if (tag.pose->alternative && !ImageDecides(*tag.pose, front_end_.params().flip)) {
      ++ambiguous;
    }
    if (tag.choice.use_alternative) ++alternatives;
  }
  return {{"detections", double(result.tags.size())},
          {"posed", posed},
          {"ambiguous", ambiguous},
          {"alternatives_chosen", alternatives},
          {"mean_rms_px", posed > 0 ? rms_sum / posed : kNaN},
          {"map_tags", map_ ? double(map_->Tags().size()) : kNaN}};
}

std::vector<PoseObservation> AprilTagNode::Poses(const NodeContext& context) const {
  const double t_s = context.Get<Frame>(kFrameSlot).t_s;
  std::vector<PoseObservation> observations;
  for (const TagResult& tag : context.Get<TagFrameResult>(kOutputSlot).tags) {
    if (!tag.pose) continue;
    PoseObservation observation;
    observation.stream = StreamName(tag.detection);
    observation.target_frame = "tag" + std::to_string(tag.detection.id);
    observation.fixed = PoseObservation::Fixed::kTarget;
    observation.t_s = t_s;
    observation.T_CX = tag.chosen().T_CT;
    // (C.9) perturbs p_CT + dt; the observation's convention perturbs Exp(dr) p_CT + dt', so
    // dt' = dt + [p_CT]x dr (as the LED tracker's node).
    Matrix6d B = Matrix6d::Identity();
    B.topRightCorner<3, 3>() = control::Skew(tag.chosen().T_CT.translation());
    observation.covariance_CX = B * tag.chosen().covariance * B.transpose();
    observations.push_back(std::move(observation));
  }
  return observations;
}

void AprilTagNode::DrawOverlay(const NodeContext& context, cv::Mat& bgr) const {
  const CameraModel& camera = front_end_.camera();
  auto point = [](const Eigen::Vector2d& px) {
    return cv::Point(static_cast<int>(std::lround(px.x())), static_cast<int>(std::lround(px.y())));
  };
  const double scale = std::max(0.35, bgr.cols / 1500.0);
  for (const TagResult& tag : context.Get<TagFrameResult>(kOutputSlot).tags) {
    std::vector<cv::Point> outline;
    for (const Eigen::Vector2d& corner : tag.detection.corners_px) outline.push_back(point(corner));
    cv::polylines(bgr, outline, true, cv::Scalar(0, 255, 255), 1, cv::LINE_AA);
    cv::putText(bgr, std::to_string(tag.detection.id), outline[0] + cv::Point(3, -3),
                cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 255, 255), 1, cv::LINE_AA);
    if (!tag.pose) continue;
    const Eigen::Isometry3d& T_CT = tag.chosen().T_CT;
    Eigen::Vector2d origin;
    if (!camera.Project(T_CT.translation(), &origin)) continue;
    const cv::Scalar colors[3] = {{0, 0, 255}, {0, 255, 0}, {255, 0, 0}};
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Vector2d tip;
      if (camera.Project(T_CT * (0.5 * tag.size_m * Eigen::Vector3d::Unit(axis)), &tip)) {
        cv::line(bgr, point(origin), point(tip), colors[axis], 2, cv::LINE_AA);
      }
    }
  }
}

std::map<std::string, std::string> AprilTagNode::Finish() {
  std::map<std::string, std::string> files;
  if (csv_) {
    csv_->Close();
    files["detections"] = kTagsCsv;
  }
  if (map_) {
    const TagMapSolveSummary summary = map_->Optimize();
    std::cerr << "apriltag map: " << map_->Tags().size() << " tags from " << map_->images_in_graph()
              << " images (" << map_->pending_images() << " not connected to the origin tag); "
              << summary << "\n";
    if (!output_directory_.empty()) {
      const std::filesystem::path directory(output_directory_);
      WriteTagMapYaml((directory / kMapYaml).string(), map_->Tags(), map_->params());
      WriteTagMapTopView((directory / kMapPng).string(), map_->Tags());
      files["map"] = kMapYaml;
      files["map_top_view"] = kMapPng;
    }
  }
  return files;
}

}  // namespace aperture::perception
