#pragma once
// A node of the frame graph (FrameGraph): a named computation that reads declared, typed slots
// and writes declared, typed slots of one frame. The source frame is the slot kFrameSlot
// ("frame", type Frame from perception/sensor_data.h).
//
// Contract for implementers:
//  - Name(), Inputs() and Outputs() are constant over the node's life (read once at graph build).
//  - Run is called once per frame, after every producer of the node's inputs has run. It must Set
//    each declared output. Different nodes may run concurrently (ParallelExecutor); one node never
//    runs concurrently with itself, so Run may keep per-node state (trackers, buffers).
//  - Metrics, Poses and DrawOverlay are called after the whole graph ran on a frame, with
//    read-only access to the node's inputs and outputs.
//  - Finish is called once after the last frame (never concurrently with Run).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "perception/graph/node_context.h"
#include "perception/graph/slot_spec.h"
#include "perception/pose_observation.h"

namespace aperture::perception {


class Node {
 public:
  virtual ~Node() = default;

  virtual std::string Name() const = 0;
  virtual std::vector<SlotSpec> Inputs() const = 0;
  virtual std::vector<SlotSpec> Outputs() const = 0;

  virtual void Run(NodeContext& context) = 0;

  // Named scalars of this frame for the CSV time series (e.g. {"mean_intensity", 97.2}). Emit the
  // same keys every frame (NaN for "not available") so the columns stay fixed.
  virtual std::map<std::string, double> Metrics(const NodeContext& /*context*/) const { return {}; }

  // Pose observations of this frame (none when nothing was found), stamped with the frame's t_s.
  virtual std::vector<PoseObservation> Poses(const NodeContext& /*context*/) const { return {}; }
  // Draws this node's results on `bgr` (CV_8UC3, the frame's size) for the overlay video.
  virtual void DrawOverlay(const NodeContext& /*context*/, cv::Mat& /*bgr*/) const {}

  // Completes the files the node writes itself into FrontEndResources::output_directory (tables
  // and maps beyond metrics and poses) and returns their names for summary.json, keyed by what
  // they hold (e.g. {"detections": "tags.csv"}). Nothing when the run gave no directory.
  virtual std::map<std::string, std::string> Finish() { return {}; }
};

}  // namespace aperture::perception
