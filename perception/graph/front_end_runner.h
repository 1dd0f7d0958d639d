#pragma once
// Front ends inside an autopilot: the same Nodes `aperture run` composes (FrontEndRegistry), run
// serially (deterministic, as SITL needs) on the frames of one camera, handing on the pose
// observations each frame produced. This is how a mission consumes perception: it never calls a
// detector itself, so `aperture run` on a recording and `aperture sim` run the same code.
//
//   FrontEndRunner front_ends = FrontEndRunner::FromRegistry(registry, {"gap"}, params, resources);
//   for each frame:  for (const PoseObservation& z : front_ends.Process(frame)) ...
//   overlay video:   front_ends.DrawOverlays(bgr);
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "perception/graph/front_end_registry.h"
#include "perception/graph/frame_graph.h"
#include "perception/graph/serial_executor.h"
#include "perception/pose_observation.h"
#include "perception/sensor_data.h"

namespace aperture::perception {

class FrontEndRunner {
 public:
  // Throws std::invalid_argument like FrameGraph for an empty or invalid set of nodes.
  explicit FrontEndRunner(std::vector<std::unique_ptr<Node>> nodes);
  // The front ends `names` from `registry`, configured by the sections of `root` named after them
  // (as `aperture run --frontends` does); throws like FrontEndRegistry::BuildGraph.
  static FrontEndRunner FromRegistry(const FrontEndRegistry& registry,
                                     const std::vector<std::string>& names,
                                     config::ParamReader& root,
                                     const FrontEndResources& resources);

  // Runs every node on `frame`; returns this frame's pose observations (nodes in topological
  // order), valid until the next call.
  const std::vector<PoseObservation>& Process(const Frame& frame);

  // The latest frame's value of slot `name` (e.g. GapNode::kOutputSlot), nullptr before the first
  // frame. Throws std::invalid_argument for an unknown slot or a wrong type T.
  template <typename T>
  const T* Latest(const std::string& name) const {
    if (!slots_ || !slots_->HasValue(name)) return nullptr;
    return &slots_->Get<T>(name, "FrontEndRunner");
  }
  // Draws every node's overlay of the latest frame onto `bgr` (CV_8UC3); nothing before one.
  void DrawOverlays(cv::Mat& bgr) const;

  int frames() const { return frames_; }
  const FrameGraph& graph() const { return *graph_; }
  // Per-node timing over every frame run so far.
  std::vector<NodeTiming> Timing() const { return executor_->Timing(); }

 private:
  explicit FrontEndRunner(FrameGraph graph);

  std::unique_ptr<FrameGraph> graph_;            // stable address for the executor
  std::unique_ptr<SerialExecutor> executor_;
  std::optional<FrameSlots> slots_;              // the latest frame's values
  std::vector<PoseObservation> observations_;    // the latest frame's poses
  int frames_ = 0;
};

}  // namespace aperture::perception
