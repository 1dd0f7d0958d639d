#pragma once
// StoppableFrameSource: the frames of another source, ending early when the run must stop
// without losing what it wrote, so `aperture run` closes its outputs the normal way:
//  - at SIGINT/SIGTERM (output::InterruptionRequested(), checked before each frame);
//  - when the source fails after it delivered frames (a camera that disconnects or stops
//    delivering, a corrupt file in the middle of a folder without --skip-bad-frames): the stream
//    ends there and the error is kept in failure(), for the run to report ("failed") once its
//    files are complete. A source that fails before its first frame throws as before.
//
//   StoppableFrameSource source(OpenFrameSource(...));
//   RunSource(source, ...);                          // frames until the end, a signal or a failure
//   ...close the CSVs and the video...
//   if (source.failure()) throw std::runtime_error(*source.failure());
#include <memory>
#include <optional>
#include <string>

#include "perception/io/frame_source.h"

namespace aperture::apps {

class StoppableFrameSource : public perception::FrameSource {
 public:
  explicit StoppableFrameSource(std::unique_ptr<perception::FrameSource> source);

  std::optional<perception::Frame> Next() override;
  std::string Describe() const override { return source_->Describe(); }
  std::optional<size_t> SizeHint() const override { return source_->SizeHint(); }
  std::vector<perception::ImuSample> TakeImuSamples() override { return source_->TakeImuSamples(); }

  // The wrapped source (its SkippedFrames()).
  const perception::FrameSource& source() const { return *source_; }
  // The error that ended the stream after frames were delivered; nullopt when it did not fail.
  const std::optional<std::string>& failure() const { return failure_; }
  std::size_t frames_delivered() const { return frames_delivered_; }

 private:
  std::unique_ptr<perception::FrameSource> source_;
  std::optional<std::string> failure_;
  std::size_t frames_delivered_ = 0;
};

}  // namespace aperture::apps
