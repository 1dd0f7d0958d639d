#pragma once
// Front end "mono_depth" (seed 003 Sec. III-A): a depth map per colour frame from the per-patch
// linear SVM (MonoDepthEstimator).
//   reads:   "frame" (Frame, CV_8UC3: run with --color)
//   writes:  "mono_depth" (MonoDepthEstimate)
//   files:   <output_dir>/mono_depth/<index>.png, 16-bit depth [mm] of the frame's size like the
//            renderer's depth/*.png (when the run has an output folder and write_depth is true)
//   metrics: mean_depth_m, min_depth_m, and Table I's e_ln, e_relative (DepthErrors) against the
//            ground truth beside the images (render output folders; NaN without ground truth)
//   overlay: the depth map (near warm, far dark) in the lower-right quarter.
// Parameters (section mono_depth): model (path of a model file; "" = the shipped forest model),
// write_depth (bool, default true).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "perception/graph/front_end_registry.h"
#include "perception/graph/node.h"
#include "perception/mono_depth/depth_errors.h"
#include "perception/mono_depth/mono_depth_estimator.h"

namespace aperture::perception {

struct MonoDepthNodeParams {
  std::string model;        // "" = DefaultMonoDepthModel()
  bool write_depth = true;  // mono_depth/<index>.png in the run's output folder
};

class MonoDepthNode final : public Node {
 public:
  static constexpr const char* kName = "mono_depth";
  static constexpr const char* kOutputSlot = "mono_depth";

  // `output_dir`: "" = write no files; `ground_truth`: depth/*.png files matched to frames by
  // index (empty = none).
  MonoDepthNode(MonoDepthModel model, std::string output_dir,
                std::vector<std::filesystem::path> ground_truth);

  static std::unique_ptr<Node> Create(config::ParamReader& params,
                                      const FrontEndResources& resources);

  std::string Name() const override { return kName; }
  std::vector<SlotSpec> Inputs() const override;
  std::vector<SlotSpec> Outputs() const override;
  void Run(NodeContext& context) override;
  std::map<std::string, double> Metrics(const NodeContext& context) const override;
  void DrawOverlay(const NodeContext& context, cv::Mat& bgr) const override;

 private:
  MonoDepthEstimator estimator_;
  std::string output_dir_;
  std::vector<std::filesystem::path> ground_truth_;
  DepthErrors last_errors_;  // of the latest frame (patches = 0 without ground truth)
};

}  // namespace aperture::perception
