#pragma once
// Front end "led": infrared-LED target pose tracking (LedTracker) on every frame.
//   needs:  a camera calibration (`aperture run --calib`)
//   params: config (LED configuration YAML path, `leds: [[x, y, z], ...]`; empty = the built-in
//           5-LED LedConfiguration::Default()), threshold, max_blobs, p3p (kneip | opengv | ap3p),
//           reprojection_threshold_px, max_rms_px
//   reads:  "frame" (Frame)
//   writes: "led" (LedTrackResult)
//   poses:  stream "led": PoseObservation of target T with the camera fixed, T_CT (p_C = T_CT * p_T)
//           with covariance [p_CT; rotation] (C.9); the TUM stream records T_CT
//   metrics: detections, correspondences, merged_detections, rms_px, status (LedTrackStatus as a
//            number: 0 tracked, 1 reinitialized, 2 no_detections, 3 no_correspondences,
//            4 ambiguous, 5 inconsistent), blob_cap_hit
//   overlay: detections (circles), reprojected LEDs (crosses) and target axes, status text.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "perception/graph/front_end_registry.h"
#include "perception/graph/node.h"
#include "perception/led/led_tracker.h"

namespace aperture::perception {

class LedTrackerNode final : public Node {
 public:
  static constexpr const char* kName = "led";
  static constexpr const char* kOutputSlot = "led";
  static constexpr const char* kPoseStream = "led";

  explicit LedTrackerNode(LedTracker tracker) : tracker_(std::move(tracker)) {}

  // Throws std::invalid_argument without a calibration, for a bad parameter or configuration;
  // std::runtime_error when the configuration file cannot be read.
  static std::unique_ptr<Node> Create(config::ParamReader& params,
                                      const FrontEndResources& resources);

  std::string Name() const override { return kName; }
  std::vector<SlotSpec> Inputs() const override;
  std::vector<SlotSpec> Outputs() const override;
  void Run(NodeContext& context) override;
  std::map<std::string, double> Metrics(const NodeContext& context) const override;
  std::vector<PoseObservation> Poses(const NodeContext& context) const override;
  void DrawOverlay(const NodeContext& context, cv::Mat& bgr) const override;

 private:
  LedTracker tracker_;
};

}  // namespace aperture::perception
