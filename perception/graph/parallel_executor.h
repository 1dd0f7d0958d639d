#pragma once
// Runs the frame graph with oneTBB: a tbb::flow::graph mirrors the node dependencies, so each node
// starts as soon as the producers of its inputs finished and independent nodes run concurrently
// on the same frame. Frames are still processed one at a time. Slot values are identical to
// SerialExecutor's for deterministic nodes. TBB headers stay in the .cc.
#include <memory>

#include "perception/graph/frame_graph_executor.h"

namespace aperture::perception {

struct ParallelExecutorParams {
  // Threads running this executor's nodes (including the calling one); 0 = all hardware threads.
  // Values above the hardware concurrency are clamped to it.
  int max_concurrency = 0;
};

class ParallelExecutor final : public FrameGraphExecutor {
 public:
  // Throws std::invalid_argument if params.max_concurrency < 0.
  explicit ParallelExecutor(FrameGraph& graph, const ParallelExecutorParams& params = {});
  ~ParallelExecutor() override;

 private:
  void RunNodes(FrameSlots& slots) override;

  struct Flow;  // the tbb::task_arena and tbb::flow::graph
  std::unique_ptr<Flow> flow_;
};

}  // namespace aperture::perception
