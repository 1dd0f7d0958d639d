#pragma once
// The frame loop `aperture run` and the Python module share: every frame of a source through a
// frame graph, the slots made from the first frame (checked against the calibration's image
// size), each frame carrying the IMU samples the source read before it (Frame::imu), and the
// caller's handler after each frame.
//
//   RunSource(*source, graph, executor, resources, max_frames,
//             [&](const Frame& frame, const FrameSlots& slots) { ...graph.CollectPoses(slots)...
//             });
#include <cstddef>
#include <functional>

#include "perception/graph/frame_graph.h"
#include "perception/graph/frame_graph_executor.h"
#include "perception/graph/front_end_registry.h"
#include "perception/io/frame_source.h"

namespace aperture::perception {

using SourceFrameHandler = std::function<void(const Frame& frame, const FrameSlots& slots)>;

// Runs `executor` (on `graph`) on the frames of `source`, at most `max_frames` (<= 0: all), and
// calls `on_frame` after each. Returns the number of frames run. Throws std::invalid_argument when
// the first frame's size differs from the calibration's (naming both), std::runtime_error naming
// the source when it produced no frame, and passes on the nodes' and the handler's errors.
std::size_t RunSource(FrameSource& source, const FrameGraph& graph, FrameGraphExecutor& executor,
                      const FrontEndResources& resources, int max_frames,
                      const SourceFrameHandler& on_frame);

}  // namespace aperture::perception
