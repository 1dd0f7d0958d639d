#include "perception/ts2p/ts2p_node.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "perception/sensor_data.h"

namespace aperture::perception {

void Ts2pNodeParams::Validate() const {
  detector.Validate();
  if (stack < 2 || stack % 2 != 0) {
    throw std::invalid_argument("ts2p.stack must be even and >= 2 (2, 4, 8), got " +
                                std::to_string(stack));
  }
  if (stride < 1 || interval < 0) {
    throw std::invalid_argument(
        "ts2p.stride must be >= 1 and ts2p.interval >= 0 (0 = "
        "stack * stride)");
  }
}

void LoadParams(config::ParamReader& reader, Ts2pNodeParams* params) {
  reader.Read("stack", &params->stack);
  reader.Read("stride", &params->stride);
  reader.Read("interval", &params->interval);
  reader.Read("gyro_derotation", &params->gyro_derotation);
  LoadParams(reader, &params->detector);
  reader.Validate(*params);
}

Ts2pNode::Ts2pNode(const Ts2pNodeParams& params, const std::string& output_dir,
                   const std::optional<CameraCalibration>& calibration)
    : params_(params),
      calibration_(calibration),
      detector_(params.detector, calibration ? calibration->camera : nullptr),
      output_dir_(output_dir) {
  params_.Validate();
  if (!output_dir_.empty()) {
    std::filesystem::create_directories(std::filesystem::path(output_dir_) / "openings");
    csv_ = std::make_unique<output::CsvWriter>(
        (std::filesystem::path(output_dir_) / "ts2p.csv").string(),
        std::vector<std::string>{"t_s", "index", "valid", "area_px", "safe_u_px", "safe_v_px",
                                 "stack", "flow", "derotated", "flow_ms", "derotation_ms",
                                 "stacking_ms", "edge_aware_ms", "segmentation_ms", "safe_point_ms",
                                 "total_ms"});
  }
}

std::unique_ptr<Node> Ts2pNode::Create(config::ParamReader& params,
                                       const FrontEndResources& resources) {
  Ts2pNodeParams node_params;
  LoadParams(params, &node_params);
  return std::make_unique<Ts2pNode>(node_params, resources.output_directory, resources.calibration);
}

std::vector<SlotSpec> Ts2pNode::Inputs() const { return {MakeSlot<Frame>(kFrameSlot)}; }

std::vector<SlotSpec> Ts2pNode::Outputs() const { return {MakeSlot<Ts2pOutput>(kOutputSlot)}; }

void Ts2pNode::Run(NodeContext& context) {
  const Frame& frame = context.Get<Frame>(kFrameSlot);
  cv::Mat gray;
  if (frame.image.channels() == 1) {
    gray = frame.image.clone();
  } else {
    cv::cvtColor(frame.image, gray, cv::COLOR_BGR2GRAY);
  }
  if (params_.gyro_derotation && !frame.imu.empty() && !calibration_) {
    throw std::invalid_argument(
        "ts2p: the frames carry IMU samples (e.g. a bag's --imu-topic) and gyro derotation needs "
        "the camera calibration and its T_BC: give --calib FILE or --camera-info-topic TOPIC, or "
        "set ts2p.gyro_derotation=false");
  }
  for (const ImuSample& sample : frame.imu) gyro_.Add(sample);
  window_.push_back({frame.index, frame.t_s, gray,
                     params_.gyro_derotation ? gyro_.OrientationAt(frame.t_s) : std::nullopt});
  const std::size_t span = static_cast<std::size_t>(params_.stack * params_.stride) + 1;
  if (window_.size() > span) window_.pop_front();
  ++frames_since_detection_;
  latest_.fresh = false;
  const int interval = params_.interval > 0 ? params_.interval : params_.stack * params_.stride;
  const bool first = latest_.detection == nullptr;
  if (window_.size() == span && (first || frames_since_detection_ >= interval)) {
    frames_since_detection_ = 0;
    const std::size_t middle = static_cast<std::size_t>(params_.stack / 2 * params_.stride);
    std::vector<cv::Mat> stack;
    for (std::size_t k = 0; k < span; k += params_.stride) {
      if (k != middle) stack.push_back(window_[k].gray);
    }
    const Buffered& reference = window_[middle];
    const std::vector<Eigen::Matrix3d> R_CkCr = StackRotations(middle);
    latest_.detection =
        std::make_shared<const Ts2pDetection>(detector_.Detect(reference.gray, stack, R_CkCr));
    latest_.fresh = true;
    latest_.derotated = !R_CkCr.empty();
    latest_.reference_index = reference.index;
    latest_.reference_t_s = reference.t_s;
    latest_.reference_image = reference.gray;
    Write(latest_);
  }
  context.Set(kOutputSlot, latest_);
}

std::vector<Eigen::Matrix3d> Ts2pNode::StackRotations(std::size_t reference) const {
  for (const Buffered& frame : window_) {
    if (!frame.R_B0B) return {};
  }
  // p_Ck = R_CB R_BkB0 R_B0Br R_BC p_Cr.
  const Eigen::Matrix3d R_BC = calibration_->T_BC.linear();
  const Eigen::Matrix3d R_B0Br = *window_[reference].R_B0B;
  std::vector<Eigen::Matrix3d> R_CkCr;
  for (std::size_t k = 0; k < window_.size(); k += params_.stride) {
    if (k == reference) continue;
    R_CkCr.push_back(R_BC.transpose() * window_[k].R_B0B->transpose() * R_B0Br * R_BC);
  }
  return R_CkCr;
}

void Ts2pNode::Write(const Ts2pOutput& output) {
  if (!csv_) return;
  const Ts2pDetection& d = *output.detection;
  if (d.valid) {
    const std::string path = (std::filesystem::path(output_dir_) / "openings" /
                              (std::to_string(output.reference_index) + ".png"))
                                 .string();
    if (!cv::imwrite(path, d.opening)) {
      throw std::runtime_error("ts2p: cannot write '" + path + "'");
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  csv_->WriteCells({output.reference_t_s, double(output.reference_index), d.valid ? 1.0 : 0.0,
                    d.area_px, d.valid ? d.safe_point_px.x() : nan,
                    d.valid ? d.safe_point_px.y() : nan, double(d.stack_size), detector_.FlowName(),
                    output.derotated ? 1.0 : 0.0, d.timing.flow_ms, d.timing.derotation_ms,
                    d.timing.stacking_ms, d.timing.edge_aware_ms, d.timing.segmentation_ms,
                    d.timing.safe_point_ms, d.timing.total_ms});
}

std::map<std::string, double> Ts2pNode::Metrics(const NodeContext& context) const {
  const auto& output = context.Get<Ts2pOutput>(kOutputSlot);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::map<std::string, double> metrics{
      {"detected", nan},        {"area_px", nan},  {"safe_u_px", nan}, {"safe_v_px", nan},
      {"reference_index", nan}, {"total_ms", nan}, {"derotated", nan}};
  if (!output.fresh) return metrics;
  const Ts2pDetection& d = *output.detection;
  metrics["detected"] = d.valid ? 1.0 : 0.0;
  metrics["reference_index"] = output.reference_index;
  metrics["total_ms"] = d.timing.total_ms;
  metrics["derotated"] = output.derotated ? 1.0 : 0.0;
  if (d.valid) {
    metrics["area_px"] = d.area_px;
    metrics["safe_u_px"] = d.safe_point_px.x();
    metrics["safe_v_px"] = d.safe_point_px.y();
  }
  return metrics;
}

void Ts2pNode::DrawOverlay(const NodeContext& context, cv::Mat& bgr) const {
  const auto& output = context.Get<Ts2pOutput>(kOutputSlot);
  if (!output.detection || !output.detection->valid) return;
  const Ts2pDetection& d = *output.detection;
  cv::polylines(bgr, std::vector<std::vector<cv::Point>>{d.contour}, true, cv::Scalar(0, 255, 0), 2,
                cv::LINE_AA);
  const cv::Point x_s(static_cast<int>(std::lround(d.safe_point_px.x())),
                      static_cast<int>(std::lround(d.safe_point_px.y())));
  cv::drawMarker(bgr, x_s, cv::Scalar(0, 0, 255), cv::MARKER_CROSS, 16, 2);
}

}  // namespace aperture::perception
