#include "perception/graph/front_end_runner.h"

#include <utility>

namespace aperture::perception {

FrontEndRunner::FrontEndRunner(std::vector<std::unique_ptr<Node>> nodes)
    : FrontEndRunner(FrameGraph(std::move(nodes))) {}

FrontEndRunner::FrontEndRunner(FrameGraph graph)
    : graph_(std::make_unique<FrameGraph>(std::move(graph))),
      executor_(std::make_unique<SerialExecutor>(*graph_)) {}

FrontEndRunner FrontEndRunner::FromRegistry(const FrontEndRegistry& registry,
                                            const std::vector<std::string>& names,
                                            config::ParamReader& root,
                                            const FrontEndResources& resources) {
  return FrontEndRunner(registry.BuildGraph(names, root, resources));
}

const std::vector<PoseObservation>& FrontEndRunner::Process(const Frame& frame) {
  if (!slots_) slots_.emplace(graph_->MakeSlots(frame));
  executor_->Run(frame, *slots_);
  ++frames_;
  observations_ = graph_->CollectPoses(*slots_);
  return observations_;
}

void FrontEndRunner::DrawOverlays(cv::Mat& bgr) const {
  if (slots_) graph_->DrawOverlays(*slots_, bgr);
}

}  // namespace aperture::perception
