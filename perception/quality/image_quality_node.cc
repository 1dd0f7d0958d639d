#include "perception/quality/image_quality_node.h"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "perception/sensor_data.h"

namespace aperture::perception {

std::unique_ptr<Node> ImageQualityNode::Create(config::ParamReader& params,
                                               const FrontEndResources& /*resources*/) {
  ImageQualityParams quality_params;
  params.Read("histogram_bins", &quality_params.histogram_bins);
  params.Read("over_exposed_level", &quality_params.over_exposed_level);
  params.Read("under_exposed_level", &quality_params.under_exposed_level);
  return std::make_unique<ImageQualityNode>(quality_params);
}

std::vector<SlotSpec> ImageQualityNode::Inputs() const { return {MakeSlot<Frame>(kFrameSlot)}; }

std::vector<SlotSpec> ImageQualityNode::Outputs() const {
  return {MakeSlot<ImageQuality>(kOutputSlot)};
}

void ImageQualityNode::Run(NodeContext& context) {
  context.Set(kOutputSlot, analyzer_.Analyze(context.Get<Frame>(kFrameSlot).image));
}

std::map<std::string, double> ImageQualityNode::Metrics(const NodeContext& context) const {
  const auto& quality = context.Get<ImageQuality>(kOutputSlot);
  std::map<std::string, double> metrics{
      {"mean_intensity", quality.mean_intensity},
      {"over_exposed_ratio", quality.over_exposed_ratio},
      {"under_exposed_ratio", quality.under_exposed_ratio},
      {"sharpness_laplacian_var", quality.sharpness_laplacian_var},
  };
  for (std::size_t bin = 0; bin < quality.histogram.size(); ++bin) {
    char key[32];
    std::snprintf(key, sizeof(key), "histogram_%02zu", bin);
    metrics[key] = quality.histogram[bin];
  }
  return metrics;
}

void ImageQualityNode::DrawOverlay(const NodeContext& context, cv::Mat& bgr) const {
  const auto& quality = context.Get<ImageQuality>(kOutputSlot);
  // Text scaled to the image so it stays legible from 320 px to 1920 px wide.
  const double scale = std::max(0.35, bgr.cols / 1500.0);
  const int line_px = static_cast<int>(std::lround(28 * scale)) + 4;
  char lines[3][96];
  std::snprintf(lines[0], sizeof(lines[0]), "mean %.1f", quality.mean_intensity);
  std::snprintf(lines[1], sizeof(lines[1]), "over %.1f%%  under %.1f%%",
                100.0 * quality.over_exposed_ratio, 100.0 * quality.under_exposed_ratio);
  std::snprintf(lines[2], sizeof(lines[2]), "sharpness %.0f", quality.sharpness_laplacian_var);
  const cv::Scalar kText(0, 255, 255);  // yellow
  for (int i = 0; i < 3; ++i) {
    const cv::Point origin(8, 8 + line_px * (i + 1));
    // Dark outline first so the text reads on bright and dark images alike.
    cv::putText(bgr, lines[i], origin, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 3,
                cv::LINE_AA);
    cv::putText(bgr, lines[i], origin, cv::FONT_HERSHEY_SIMPLEX, scale, kText, 1, cv::LINE_AA);
  }
  // Histogram bars below the text, each bar's height relative to the fullest bin.
  const int bins = static_cast<int>(quality.histogram.size());
  const double fullest = *std::max_element(quality.histogram.begin(), quality.histogram.end());
  const int bar_px = std::max(2, line_px / 3);
  const int height_px = 2 * line_px;
  const cv::Point base(8, 8 + line_px * 3 + 8 + height_px);
  cv::rectangle(bgr, cv::Rect(base.x, base.y - height_px, bins * bar_px, height_px),
                cv::Scalar(0, 0, 0), cv::FILLED);
  for (int bin = 0; bin < bins && fullest > 0.0; ++bin) {
    const int h = static_cast<int>(std::lround(height_px * quality.histogram[bin] / fullest));
    cv::rectangle(bgr, cv::Rect(base.x + bin * bar_px, base.y - h, bar_px, h), kText, cv::FILLED);
  }
}

}  // namespace aperture::perception
