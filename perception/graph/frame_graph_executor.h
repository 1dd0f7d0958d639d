#pragma once
// Runs a FrameGraph once per frame and records per-node wall-clock durations. Implementations:
// SerialExecutor (deterministic, topological order) and ParallelExecutor (oneTBB, independent
// nodes concurrently). Both give identical slot values for deterministic nodes.
//
// Typical use (the `aperture run` loop):
//   FrameGraph graph = registry.BuildGraph({"image_quality"});
//   SerialExecutor executor(graph);
//   FrameSlots slots = graph.MakeSlots(first_frame);
//   for each frame: executor.Run(frame, slots);
//                   csv.Write(graph.CollectMetrics(slots));
//                   video.write(graph.RenderOverlay(slots));
//   summary["timing"] = executor.Timing();  // + executor.FrameTiming() for the whole graph
#include <chrono>
#include <cstddef>
#include <vector>

#include "perception/graph/frame_graph.h"
#include "perception/graph/frame_slots.h"
#include "perception/graph/timing_stats.h"
#include "perception/sensor_data.h"

namespace aperture::perception {

class FrameGraphExecutor {
 public:
  // `graph` must outlive the executor; the executor runs its nodes (they may keep state).
  explicit FrameGraphExecutor(FrameGraph& graph);
  virtual ~FrameGraphExecutor() = default;
  FrameGraphExecutor(const FrameGraphExecutor&) = delete;
  FrameGraphExecutor& operator=(const FrameGraphExecutor&) = delete;

  // Runs every node once on `frame`, writing into `slots` (made by graph.MakeSlots; its values are
  // replaced). Rethrows the first exception a node throws (that frame is then missing from
  // FrameTiming; nodes that completed keep their durations).
  void Run(const Frame& frame, FrameSlots& slots);
  // Convenience: a fresh slot table per frame.
  FrameSlots Run(const Frame& frame);

  // Per node (topological order) over all frames run so far: count, median, p95, max [s]
  // (median and p95 over an evenly spread subset on very long runs: DurationRecord).
  std::vector<NodeTiming> Timing() const;
  // Whole-graph wall time per frame [s].
  TimingStats FrameTiming() const;

 protected:
  // Runs node `index` on `slots` and records its duration. Safe to call concurrently for
  // different nodes.
  void RunNode(std::size_t index, FrameSlots& slots);
  virtual void RunNodes(FrameSlots& slots) = 0;

  FrameGraph& graph_;

 private:
  std::vector<DurationRecord> node_durations_;  // [node index]
  DurationRecord frame_durations_;
};

}  // namespace aperture::perception
