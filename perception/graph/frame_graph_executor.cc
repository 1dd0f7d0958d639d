#include "perception/graph/frame_graph_executor.h"

#include "perception/elapsed_time.h"

namespace aperture::perception {

FrameGraphExecutor::FrameGraphExecutor(FrameGraph& graph)
    : graph_(graph), node_durations_(graph.size()) {}

void FrameGraphExecutor::Run(const Frame& frame, FrameSlots& slots) {
  const auto start = std::chrono::steady_clock::now();
  graph_.ResetSlots(frame, slots);
  RunNodes(slots);
  frame_durations_.Add(SecondsSince(start));
}

FrameSlots FrameGraphExecutor::Run(const Frame& frame) {
  FrameSlots slots = graph_.MakeSlots(frame);
  Run(frame, slots);
  return slots;
}

void FrameGraphExecutor::RunNode(std::size_t index, FrameSlots& slots) {
  NodeContext context = graph_.ContextFor(index, slots);
  const auto start = std::chrono::steady_clock::now();
  graph_.node(index).Run(context);
  node_durations_[index].Add(SecondsSince(start));
}

std::vector<NodeTiming> FrameGraphExecutor::Timing() const {
  std::vector<NodeTiming> table;
  for (std::size_t index : graph_.topological_order()) {
    table.push_back({graph_.declaration(index).name, node_durations_[index].Summary()});
  }
  return table;
}

TimingStats FrameGraphExecutor::FrameTiming() const { return frame_durations_.Summary(); }

}  // namespace aperture::perception
