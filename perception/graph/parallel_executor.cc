#include "perception/graph/parallel_executor.h"

#include <tbb/flow_graph.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "perception/graph/happens_before.h"

namespace aperture::perception {

namespace {
// The start of every frame's tasks, for ThreadSanitizer: a key that a task can name before it
// reads its own captures (which the constructing thread wrote).
const char kFrameHandOff = 0;
}  // namespace

struct ParallelExecutor::Flow {
  // Requests above the machine's concurrency are clamped: oneTBB would cap them anyway (with a
  // warning on stderr).
  explicit Flow(int max_concurrency)
      : arena(max_concurrency == 0 ? tbb::task_arena::automatic
                                   : std::min(max_concurrency, tbb::info::default_concurrency())) {}

  tbb::task_arena arena;
  std::unique_ptr<tbb::flow::graph> graph;
  std::unique_ptr<tbb::flow::broadcast_node<tbb::flow::continue_msg>> start;
  std::vector<std::unique_ptr<tbb::flow::continue_node<tbb::flow::continue_msg>>> nodes;

  // Per frame: the slots being filled and the first failure. After a failure the remaining node
  // bodies return without running, so the rethrown error is the original one, not a follow-up
  // "slot has no value".
  FrameSlots* slots = nullptr;
  std::mutex error_mutex;
  std::exception_ptr error;
};

ParallelExecutor::ParallelExecutor(FrameGraph& graph, const ParallelExecutorParams& params)
    : FrameGraphExecutor(graph) {
  if (params.max_concurrency < 0) {
    throw std::invalid_argument(
        "ParallelExecutor: max_concurrency = " + std::to_string(params.max_concurrency) +
        " is negative; use 0 for all hardware threads");
  }
  flow_ = std::make_unique<Flow>(params.max_concurrency);
  Flow& flow = *flow_;
  // The flow graph runs its tasks in the arena it was constructed in.
  flow.arena.execute([this, &flow] {
    flow.graph = std::make_unique<tbb::flow::graph>();
    flow.start = std::make_unique<tbb::flow::broadcast_node<tbb::flow::continue_msg>>(*flow.graph);
    for (std::size_t index = 0; index < graph_.size(); ++index) {
      flow.nodes.push_back(std::make_unique<tbb::flow::continue_node<tbb::flow::continue_msg>>(
          *flow.graph, [this, index](const tbb::flow::continue_msg&) {
            // The graph's edges, spelled out for ThreadSanitizer: a node starts after the frame
            // was handed over and after its producers ended; wait_for_all() after every node.
            HappensAfter(&kFrameHandOff);
            Flow& state = *flow_;
            for (std::size_t producer : graph_.dependencies(index)) {
              HappensAfter(state.nodes[producer].get());
            }
            bool failed_before = false;
            {
              std::lock_guard<std::mutex> lock(state.error_mutex);
              failed_before = static_cast<bool>(state.error);
            }
            if (!failed_before) {
              try {
                RunNode(index, *state.slots);
              } catch (...) {
                std::lock_guard<std::mutex> lock(state.error_mutex);
                if (!state.error) state.error = std::current_exception();
              }
            }
            HappensBefore(state.nodes[index].get());  // on every path, skipped nodes too
          }));
    }
    for (std::size_t index = 0; index < graph_.size(); ++index) {
      const auto& dependencies = graph_.dependencies(index);
      if (dependencies.empty()) {
        tbb::flow::make_edge(*flow.start, *flow.nodes[index]);
      }
      for (std::size_t dependency : dependencies) {
        tbb::flow::make_edge(*flow.nodes[dependency], *flow.nodes[index]);
      }
    }
  });
}

ParallelExecutor::~ParallelExecutor() {
  flow_->arena.execute([this] { flow_->graph->wait_for_all(); });
  for (const auto& node : flow_->nodes) HappensAfter(node.get());
}

void ParallelExecutor::RunNodes(FrameSlots& slots) {
  Flow& flow = *flow_;
  flow.slots = &slots;
  flow.error = nullptr;
  HappensBefore(&kFrameHandOff);
  flow.arena.execute([&flow] {
    flow.start->try_put(tbb::flow::continue_msg());
    flow.graph->wait_for_all();
  });
  for (const auto& node : flow.nodes) HappensAfter(node.get());
  flow.slots = nullptr;
  if (flow.error) std::rethrow_exception(flow.error);
}

}  // namespace aperture::perception
