#include "perception/graph/source_run.h"

#include <optional>
#include <stdexcept>

#include "perception/camera/calibration_io.h"

namespace aperture::perception {

std::size_t RunSource(FrameSource& source, const FrameGraph& graph, FrameGraphExecutor& executor,
                      const FrontEndResources& resources, int max_frames,
                      const SourceFrameHandler& on_frame) {
  std::optional<FrameSlots> slots;
  std::size_t frames = 0;
  while (max_frames <= 0 || frames < static_cast<std::size_t>(max_frames)) {
    std::optional<Frame> frame = source.Next();
    if (!frame) break;
    frame->imu = source.TakeImuSamples();
    if (!slots) {
      if (resources.calibration) {
        CheckCalibrationImageSize(*resources.calibration, frame->image.cols, frame->image.rows);
      }
      slots = graph.MakeSlots(*frame);
    }
    executor.Run(*frame, *slots);
    ++frames;
    on_frame(*frame, *slots);
  }
  if (frames == 0) {
    throw std::runtime_error(source.Describe() + " produced no frames");
  }
  return frames;
}

}  // namespace aperture::perception
