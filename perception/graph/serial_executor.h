#pragma once
// Runs the frame graph's nodes one after another in FrameGraph::topological_order(): fully
// deterministic, used by tests and SITL.
#include "perception/graph/frame_graph_executor.h"

namespace aperture::perception {

class SerialExecutor final : public FrameGraphExecutor {
 public:
  explicit SerialExecutor(FrameGraph& graph) : FrameGraphExecutor(graph) {}

 private:
  void RunNodes(FrameSlots& slots) override;
};

}  // namespace aperture::perception
