#pragma once
// Front end "gap": runs GapDetector (seed 000, Sec. III-A) on every frame.
//   reads:   "frame" (Frame)
//   writes:  "gap" (GapDetection: T_CG, covariance, status, reprojection RMS)
//   poses:   stream "gap": PoseObservation of target G (fixed; gap_detector.h defines G), T_CG
//            with the detector's covariance; the TUM stream records the camera's pose in the gap
//            frame T_GC (covariance of the left perturbation in G); none when missed.
//   metrics: detected (0/1), reprojection_rms_px (corners), edge_rms_px, distance_m (|p_CG|);
//            NaN when missed.
//   overlay: the 8 sub-pixel corners and the axes of G (x red, y green, z blue, 0.3 m), drawn
//            through the camera model (curved on a fisheye).
// Needs the camera calibration (`aperture run --calib`); parameters: GapDetectorParams fields.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "perception/gap/gap_detector.h"
#include "perception/graph/front_end_registry.h"
#include "perception/graph/node.h"

namespace aperture::perception {

class GapNode final : public Node {
 public:
  static constexpr const char* kName = "gap";
  static constexpr const char* kOutputSlot = "gap";

  GapNode(const GapDetectorParams& params, std::shared_ptr<const CameraModel> camera)
      : detector_(params, std::move(camera)) {}

  // Throws std::invalid_argument without a calibration or with bad parameters.
  static std::unique_ptr<Node> Create(config::ParamReader& params, const FrontEndResources& resources);

  std::string Name() const override { return kName; }
  std::vector<SlotSpec> Inputs() const override;
  std::vector<SlotSpec> Outputs() const override;
  void Run(NodeContext& context) override;
  std::map<std::string, double> Metrics(const NodeContext& context) const override;
  std::vector<PoseObservation> Poses(const NodeContext& context) const override;
  void DrawOverlay(const NodeContext& context, cv::Mat& bgr) const override;

 private:
  GapDetector detector_;
};

}  // namespace aperture::perception
