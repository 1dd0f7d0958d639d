// Executor overhead: per-frame cost of running N nearly empty nodes (each reads the frame and
// writes one int), so the time is the executors' bookkeeping, not the nodes' work. Shapes: a fan
// of N independent nodes (best case for ParallelExecutor) and a chain of N (no parallelism).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "perception/graph/frame_graph.h"
#include "perception/graph/parallel_executor.h"
#include "perception/graph/serial_executor.h"

namespace aperture::perception {
namespace {

class TinyNode final : public Node {
 public:
  TinyNode(int index, bool chained) : index_(index), chained_(chained) {}
  std::string Name() const override { return "n" + std::to_string(index_); }
  std::vector<SlotSpec> Inputs() const override {
    if (chained_ && index_ > 0) return {MakeSlot<int>("s" + std::to_string(index_ - 1))};
    return {MakeSlot<Frame>(kFrameSlot)};
  }
  std::vector<SlotSpec> Outputs() const override {
    return {MakeSlot<int>("s" + std::to_string(index_))};
  }
  void Run(NodeContext& context) override { context.Set("s" + std::to_string(index_), index_); }

 private:
  int index_;
  bool chained_;
};

FrameGraph MakeGraph(int nodes, bool chained) {
  std::vector<std::unique_ptr<Node>> list;
  for (int i = 0; i < nodes; ++i) list.push_back(std::make_unique<TinyNode>(i, chained));
  return FrameGraph(std::move(list));
}

template <typename Executor>
void RunFrames(benchmark::State& state, bool chained) {
  FrameGraph graph = MakeGraph(static_cast<int>(state.range(0)), chained);
  Executor executor(graph);
  Frame frame;
  FrameSlots slots = graph.MakeSlots(frame);
  for (auto _ : state) {
    executor.Run(frame, slots);
    benchmark::ClobberMemory();
  }
}

void BM_SerialFan(benchmark::State& state) { RunFrames<SerialExecutor>(state, false); }
void BM_ParallelFan(benchmark::State& state) { RunFrames<ParallelExecutor>(state, false); }
void BM_SerialChain(benchmark::State& state) { RunFrames<SerialExecutor>(state, true); }
void BM_ParallelChain(benchmark::State& state) { RunFrames<ParallelExecutor>(state, true); }
BENCHMARK(BM_SerialFan)->Arg(1)->Arg(4)->Arg(16)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ParallelFan)->Arg(1)->Arg(4)->Arg(16)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SerialChain)->Arg(4)->Arg(16)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ParallelChain)->Arg(4)->Arg(16)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace aperture::perception
