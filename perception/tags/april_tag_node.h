#pragma once
// Front end "apriltag": AprilTag detection, pose and flip resolution (TagFrontEnd) on every
// frame, optionally the tag map (TagMap).
//   needs:  a camera calibration (`aperture run --calib`); a tag size (apriltag.size_m / sizes)
//   params: tag_front_end_params_io.h (detector, families, sizes, flip, map, mapping)
//   reads:  "frame" (Frame, 8-bit gray)
//   writes: "apriltag" (TagFrameResult)
//   poses:  one PoseObservation per tag and frame, stream "tag<id>" ("<family>_tag<id>" with
//           several families), T_CX = T_CT (p_C = T_CT * p_T), fixed target (the TUM stream
//           records T_TC, the camera in the tag frame), covariance in PoseObservation's
//           convention
//   metrics: detections, posed, ambiguous (candidates with ambiguity_ratio above the
//            resolver's threshold), alternatives_chosen, mean_rms_px, map_tags
//   files (with an output directory): tags.csv, one row per detection: t_s, index, family, id,
//           u0 v0 .. u3 v3 (distorted px, library order), tx ty tz qx qy qz qw (T_CT of the
//           chosen candidate; empty without pose), decision_margin, ambiguity_ratio, then
//           flip_decision and rms_px; with map=true tag_map.yaml and tag_map.png at Finish.
//   overlay: tag outlines, ids, axes of the chosen pose (x red, y green, z blue).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "output/csv_writer.h"
#include "perception/graph/front_end_registry.h"
#include "perception/graph/node.h"
#include "perception/tags/tag_front_end.h"
#include "perception/tags/tag_map.h"

namespace aperture::perception {

class AprilTagNode final : public Node {
 public:
  static constexpr const char* kName = "apriltag";
  static constexpr const char* kOutputSlot = "apriltag";

  // map: build a TagMap with map_params. output_directory empty: no files.
  AprilTagNode(TagFrontEnd front_end, std::optional<TagMapParams> map_params,
               const std::string& output_directory);

  // Throws std::invalid_argument without a calibration, for a bad parameter or detector name.
  static std::unique_ptr<Node> Create(config::ParamReader& params,
                                      const FrontEndResources& resources);

  std::string Name() const override { return kName; }
  std::vector<SlotSpec> Inputs() const override;
  std::vector<SlotSpec> Outputs() const override;
  void Run(NodeContext& context) override;
  std::map<std::string, double> Metrics(const NodeContext& context) const override;
  std::vector<PoseObservation> Poses(const NodeContext& context) const override;
  void DrawOverlay(const NodeContext& context, cv::Mat& bgr) const override;
  std::map<std::string, std::string> Finish() override;

  const TagMap* map() const { return map_.get(); }
  std::string StreamName(const TagDetection& detection) const;

 private:
  void WriteRows(const Frame& frame, const TagFrameResult& result);

  TagFrontEnd front_end_;
  std::unique_ptr<TagMap> map_;
  std::string output_directory_;
  std::unique_ptr<output::CsvWriter> csv_;
};

}  // namespace aperture::perception
