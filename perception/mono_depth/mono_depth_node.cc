#include "perception/mono_depth/mono_depth_node.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "perception/mono_depth/rendered_depth_folder.h"
#include "perception/sensor_data.h"

namespace aperture::perception {

MonoDepthNode::MonoDepthNode(MonoDepthModel model, std::string output_dir,
                             std::vector<std::filesystem::path> ground_truth)
    : estimator_(std::move(model)),
      output_dir_(std::move(output_dir)),
      ground_truth_(std::move(ground_truth)) {
  if (!output_dir_.empty()) std::filesystem::create_directories(output_dir_ + "/" + kName);
}

std::unique_ptr<Node> MonoDepthNode::Create(config::ParamReader& params,
                                            const FrontEndResources& resources) {
  MonoDepthNodeParams node_params;
  params.Read("model", &node_params.model);
  params.Read("write_depth", &node_params.write_depth);
  MonoDepthModel model =
      node_params.model.empty() ? DefaultMonoDepthModel() : MonoDepthModel::Load(node_params.model);
  std::vector<std::filesystem::path> ground_truth;
  if (const auto depth_folder = FindDepthBesideImages(resources.source)) {
    ground_truth = ListPngFiles(*depth_folder);
  }
  return std::make_unique<MonoDepthNode>(std::move(model),
                                         node_params.write_depth ? resources.output_directory : "",
                                         std::move(ground_truth));
}

std::vector<SlotSpec> MonoDepthNode::Inputs() const { return {MakeSlot<Frame>(kFrameSlot)}; }

std::vector<SlotSpec> MonoDepthNode::Outputs() const {
  return {MakeSlot<MonoDepthEstimate>(kOutputSlot)};
}

void MonoDepthNode::Run(NodeContext& context) {
  const Frame& frame = context.Get<Frame>(kFrameSlot);
  MonoDepthEstimate estimate = estimator_.Estimate(frame.image);
  last_errors_ = DepthErrors{};
  if (frame.index >= 0 && std::size_t(frame.index) < ground_truth_.size()) {
    const std::filesystem::path& file = ground_truth_[frame.index];
    const cv::Mat depth_mm = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
    if (depth_mm.empty()) {
      throw std::invalid_argument("mono_depth: cannot read ground-truth depth '" + file.string() +
                                  "'");
    }
    const MonoDepthModel& model = estimator_.model();
    last_errors_ =
        CompareDepth(estimate.depth_m, PatchDepthFromMillimetres(depth_mm, estimate.grid),
                     model.labels().MinDepth(), model.labels().MaxDepth());
  }
  if (!output_dir_.empty()) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.png", frame.index);
    const std::string path = output_dir_ + "/" + kName + "/" + name;
    if (!cv::imwrite(path, DepthImageMillimetres(estimate, frame.image.size()))) {
      throw std::runtime_error("mono_depth: cannot write '" + path + "'");
    }
  }
  context.Set(kOutputSlot, std::move(estimate));
}

std::map<std::string, double> MonoDepthNode::Metrics(const NodeContext& context) const {
  const auto& estimate = context.Get<MonoDepthEstimate>(kOutputSlot);
  double min_depth = 0.0, max_depth = 0.0;
  cv::minMaxLoc(estimate.depth_m, &min_depth, &max_depth);
  return {{"mean_depth_m", cv::mean(estimate.depth_m)[0]},
          {"min_depth_m", min_depth},
          {"e_ln", last_errors_.MeanLn()},
          {"e_relative", last_errors_.MeanRelative()}};
}

void MonoDepthNode::DrawOverlay(const NodeContext& context, cv::Mat& bgr) const {
  const auto& estimate = context.Get<MonoDepthEstimate>(kOutputSlot);
  const MonoDepthModel& model = estimator_.model();
  // ln-depth scaled to 0..255, near = 255, so the colormap shows near warm and far dark.
  const double ln_min = std::log(model.labels().MinDepth());
  const double ln_span = std::log(model.labels().MaxDepth()) - ln_min;
  cv::Mat ln_depth, gray, colour;
  cv::log(estimate.depth_m, ln_depth);
  ln_depth.convertTo(gray, CV_8U, -255.0 / ln_span, 255.0 + 255.0 * ln_min / ln_span);
  cv::applyColorMap(gray, colour, cv::COLORMAP_INFERNO);
  const cv::Rect inset(bgr.cols / 2, bgr.rows / 2, bgr.cols - bgr.cols / 2,
                       bgr.rows - bgr.rows / 2);
  cv::resize(colour, bgr(inset), inset.size(), 0, 0, cv::INTER_NEAREST);
  cv::rectangle(bgr, inset, cv::Scalar(255, 255, 255), 1);
}

}  // namespace aperture::perception
