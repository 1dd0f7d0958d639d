#include "perception/ts2p/gap_tracker_node.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "perception/sensor_data.h"
#include "perception/ts2p/ts2p_node.h"

namespace aperture::perception {
namespace {

cv::Point ToPoint(const Eigen::Vector2d& p) {
  return {static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))};
}

}  // namespace

GapTrackerNode::GapTrackerNode(const LabelTrackerParams& params, const std::string& output_dir)
    : tracker_(params) {
  if (!output_dir.empty()) {
    csv_ = std::make_unique<output::CsvWriter>(
        (std::filesystem::path(output_dir) / "gap_tracker.csv").string(),
        std::vector<std::string>{"t_s", "index", "valid", "safe_u_px", "safe_v_px", "measured_u_px",
                                 "measured_v_px", "source", "foe_u_px", "foe_v_px", "divergence",
                                 "foreground_corners", "background_corners", "foreground_reset",
                                 "background_reset", "propagation_ms", "klt_ms"});
  }
}

std::unique_ptr<Node> GapTrackerNode::Create(config::ParamReader& params,
                                             const FrontEndResources& resources) {
  LabelTrackerParams tracker_params;
  LoadParams(params, &tracker_params);
  return std::make_unique<GapTrackerNode>(tracker_params, resources.output_directory);
}

std::vector<SlotSpec> GapTrackerNode::Inputs() const {
  return {MakeSlot<Frame>(kFrameSlot), MakeSlot<Ts2pOutput>(Ts2pNode::kOutputSlot)};
}

std::vector<SlotSpec> GapTrackerNode::Outputs() const {
  return {MakeSlot<OpeningTrack>(kOutputSlot)};
}

void GapTrackerNode::Run(NodeContext& context) {
  const Frame& frame = context.Get<Frame>(kFrameSlot);
  const auto& ts2p = context.Get<Ts2pOutput>(Ts2pNode::kOutputSlot);
  cv::Mat gray;
  if (frame.image.channels() == 1) {
    gray = frame.image;
  } else {
    cv::cvtColor(frame.image, gray, cv::COLOR_BGR2GRAY);
  }
  if (ts2p.fresh && ts2p.detection->valid) {
    const Ts2pDetection& d = *ts2p.detection;
    tracker_.Initialize(ts2p.reference_image, d.opening, d.safe_point_px, d.contour,
                        ts2p.reference_t_s, ts2p.reference_index);
  }
  OpeningTrack track = tracker_.Track(gray, frame.t_s, frame.index);
  Write(track);
  context.Set(kOutputSlot, std::move(track));
}

void GapTrackerNode::Write(const OpeningTrack& t) {
  if (!csv_) return;
  csv_->WriteCells({t.t_s, double(t.index), t.valid ? 1.0 : 0.0, t.safe_point_px.x(),
                    t.safe_point_px.y(), t.safe_point_measured_px.x(), t.safe_point_measured_px.y(),
                    std::string(1, t.safe_point_source), t.foe_px.x(), t.foe_px.y(), t.divergence,
                    double(t.foreground_corners), double(t.background_corners),
                    t.foreground_reset ? 1.0 : 0.0, t.background_reset ? 1.0 : 0.0,
                    t.propagation_ms, t.klt_ms});
}

std::map<std::string, double> GapTrackerNode::Metrics(const NodeContext& context) const {
  const auto& t = context.Get<OpeningTrack>(kOutputSlot);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto value = [&](double v) { return t.valid ? v : nan; };
  return {{"valid", t.valid ? 1.0 : 0.0},
          {"safe_u_px", value(t.safe_point_px.x())},
          {"safe_v_px", value(t.safe_point_px.y())},
          {"foe_u_px", value(t.foe_px.x())},
          {"foe_v_px", value(t.foe_px.y())},
          {"divergence", value(t.divergence)},
          {"foreground_corners", value(t.foreground_corners)},
          {"background_corners", value(t.background_corners)},
          {"propagation_ms", value(t.propagation_ms)},
          {"klt_ms", value(t.klt_ms)}};
}

void GapTrackerNode::DrawOverlay(const NodeContext& context, cv::Mat& bgr) const {
  const auto& t = context.Get<OpeningTrack>(kOutputSlot);
  if (!t.valid) return;
  for (const cv::Point2f& c : tracker_.ForegroundCorners()) {
    cv::circle(bgr, c, 2, cv::Scalar(255, 0, 0), -1);
  }
  for (const cv::Point2f& c : tracker_.BackgroundCorners()) {
    cv::circle(bgr, c, 2, cv::Scalar(0, 255, 0), -1);
  }
  std::vector<cv::Point> contour;
  for (const Eigen::Vector2d& p : t.contour_px) contour.push_back(ToPoint(p));
  if (contour.size() > 1) {
    cv::polylines(bgr, std::vector<std::vector<cv::Point>>{contour}, true, cv::Scalar(0, 255, 255),
                  1, cv::LINE_AA);
  }
  cv::drawMarker(bgr, ToPoint(t.safe_point_px), cv::Scalar(0, 0, 255), cv::MARKER_TILTED_CROSS, 14,
                 2);
}

}  // namespace aperture::perception
