#pragma once
// The frame graph: a validated DAG of nodes (Node) connected by named, typed slots. The root slot
// kFrameSlot ("frame", type Frame) is provided by the source; every other slot has exactly one
// producing node. Executors (SerialExecutor, ParallelExecutor) run it once per frame.
//
// Building validates the graph and throws std::invalid_argument naming the nodes and slot on:
// an empty or repeated node name, a node reading a slot nobody produces, a producer/consumer type
// mismatch, two producers of one slot (the source counts as producer of "frame"), or a cycle.
#include <cstddef>
#include <map>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "perception/graph/frame_slots.h"
#include "perception/graph/node.h"
#include "perception/graph/node_context.h"
#include "perception/sensor_data.h"

namespace aperture::perception {

class FrameGraph {
 public:
  // Nodes are identified by their index in `nodes` (insertion order).
  explicit FrameGraph(std::vector<std::unique_ptr<Node>> nodes);

  std::size_t size() const { return nodes_.size(); }
  Node& node(std::size_t index) { return *nodes_.at(index); }
  const Node& node(std::size_t index) const { return *nodes_.at(index); }
  const NodeDeclaration& declaration(std::size_t index) const { return declarations_.at(index); }

  // Execution order: every node after the producers of its inputs; among nodes that are ready at
  // the same time, the earlier inserted one first (stable, deterministic).
  const std::vector<std::size_t>& topological_order() const { return topological_order_; }
  std::vector<std::string> TopologicalNames() const;
  // Nodes whose outputs node `index` reads (sorted, without duplicates; the source is not listed).
  const std::vector<std::size_t>& dependencies(std::size_t index) const {
    return dependencies_.at(index);
  }

  // An empty slot table for one frame with "frame" set.
  FrameSlots MakeSlots(const Frame& frame) const;
  // Empties `slots` (made by MakeSlots) and sets "frame": reuse between frames.
  void ResetSlots(const Frame& frame, FrameSlots& slots) const;
  NodeContext ContextFor(std::size_t index, FrameSlots& slots) const;

  // After a frame ran: every node's Metrics, keyed "<node>.<metric>" (nodes in topological order).
  std::map<std::string, double> CollectMetrics(const FrameSlots& slots) const;
  // After a frame ran: every node's pose observations (nodes in topological order).
  std::vector<PoseObservation> CollectPoses(const FrameSlots& slots) const;
  // After the last frame: every node's Finish, keyed "<node>.<key>" (file names).
  std::map<std::string, std::string> Finish();
  // After a frame ran: every node's DrawOverlay in topological order onto `bgr` (CV_8UC3).
  void DrawOverlays(const FrameSlots& slots, cv::Mat& bgr) const;
  // A BGR copy of the frame's image (gray is expanded) with every overlay drawn: one frame of the
  // overlay video. Throws std::invalid_argument if the frame image is empty or not 8-bit.
  cv::Mat RenderOverlay(const FrameSlots& slots) const;

 private:
  std::vector<std::unique_ptr<Node>> nodes_;
  std::vector<NodeDeclaration> declarations_;
  std::vector<SlotSpec> slots_;  // every slot, "frame" first
  std::vector<std::vector<std::size_t>> dependencies_;
  std::vector<std::size_t> topological_order_;
};

}  // namespace aperture::perception
