#pragma once
// Front end "image_quality": runs ImageQualityAnalyzer on every frame.
//   reads:  "frame" (Frame)
//   writes: "image_quality" (ImageQuality)
//   metrics: mean_intensity, over_exposed_ratio, under_exposed_ratio, sharpness_laplacian_var,
//            histogram_00 .. histogram_<bins-1>
//   overlay: the numbers and a small histogram in the top-left corner.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "perception/graph/node.h"
#include "config/param_reader.h"
#include "perception/graph/front_end_registry.h"
#include "perception/quality/image_quality_analyzer.h"

namespace aperture::perception {

class ImageQualityNode final : public Node {
 public:
  static constexpr const char* kName = "image_quality";
  static constexpr const char* kOutputSlot = "image_quality";

  explicit ImageQualityNode(const ImageQualityParams& params = {}) : analyzer_(params) {}

  // Parameters: histogram_bins, over_exposed_level, under_exposed_level (ImageQualityParams);
  // unknown keys or unparsable values throw std::invalid_argument.
  static std::unique_ptr<Node> Create(config::ParamReader& params, const FrontEndResources&);

  std::string Name() const override { return kName; }
  std::vector<SlotSpec> Inputs() const override;
  std::vector<SlotSpec> Outputs() const override;
  void Run(NodeContext& context) override;
  std::map<std::string, double> Metrics(const NodeContext& context) const override;
  void DrawOverlay(const NodeContext& context, cv::Mat& bgr) const override;

 private:
  ImageQualityAnalyzer analyzer_;
};

}  // namespace aperture::perception
