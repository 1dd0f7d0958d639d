#include "apps/stoppable_frame_source.h"

#include <exception>
#include <utility>

#include "output/interruption.h"

namespace aperture::apps {

StoppableFrameSource::StoppableFrameSource(std::unique_ptr<perception::FrameSource> source)
    : source_(std::move(source)) {}

std::optional<perception::Frame> StoppableFrameSource::Next() {
  if (failure_ || output::InterruptionRequested()) return std::nullopt;
  std::optional<perception::Frame> frame;
  try {
    frame = source_->Next();
  } catch (const std::exception& e) {
    if (frames_delivered_ == 0) throw;
    failure_ = std::string(e.what()) + " (after " + std::to_string(frames_delivered_) +
               " frames; the outputs hold those frames)";
    return std::nullopt;
  }
  if (frame) ++frames_delivered_;
  return frame;
}

}  // namespace aperture::apps
