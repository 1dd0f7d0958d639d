#pragma once
// Front end "gap_tracker": label tracking of the TS²P opening (LabelTracker, seed 002 Sec. III,
// Alg. 1). Needs front end "ts2p" in the same graph. On every fresh valid ts2p detection it
// (re)initializes F and B in the detection's reference frame and tracks from there into the
// current frame; on the other frames it tracks frame to frame.
//   reads:   "frame" (Frame), "ts2p" (Ts2pOutput)
//   writes:  "gap_tracker" (OpeningTrack, opening_track.h)
//   metrics: valid, safe_u_px, safe_v_px, foe_u_px, foe_v_px, divergence, foreground_corners,
//            background_corners, propagation_ms, klt_ms (NaN before the first detection).
//   files:   (with FrontEndResources::output_directory) gap_tracker.csv, one row per frame: t_s,
//            index, valid, x_s (filtered and measured), source (F/B), FOE, divergence, corner
//            counts, resets, time per stage.
//   overlay: F corners (blue), B corners (green), the propagated contour (yellow), x_s (red).
// Parameters (section `gap_tracker`): LabelTrackerParams fields, `filter` section.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "output/csv_writer.h"
#include "perception/graph/front_end_registry.h"
#include "perception/graph/node.h"
#include "perception/ts2p/label_tracker.h"

namespace aperture::perception {

class GapTrackerNode final : public Node {
 public:
  static constexpr const char* kName = "gap_tracker";
  static constexpr const char* kOutputSlot = "gap_tracker";

  GapTrackerNode(const LabelTrackerParams& params, const std::string& output_dir);

  static std::unique_ptr<Node> Create(config::ParamReader& params,
                                      const FrontEndResources& resources);

  std::string Name() const override { return kName; }
  std::vector<SlotSpec> Inputs() const override;
  std::vector<SlotSpec> Outputs() const override;
  void Run(NodeContext& context) override;
  std::map<std::string, double> Metrics(const NodeContext& context) const override;
  void DrawOverlay(const NodeContext& context, cv::Mat& bgr) const override;

 private:
  void Write(const OpeningTrack& track);

  LabelTracker tracker_;
  std::unique_ptr<output::CsvWriter> csv_;
};

}  // namespace aperture::perception
