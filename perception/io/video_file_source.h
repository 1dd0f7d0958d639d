#pragma once
// VideoFileSource: frames of a video file decoded by cv::VideoCapture (FFmpeg / GStreamer backends
// of the installed OpenCV: .avi, .mp4, .mkv, ...).
//
// Timestamps [s]: with options.fps > 0, t_i = i / fps (for files whose timestamps are broken);
// otherwise the container's presentation time of each frame (CAP_PROP_POS_MSEC / 1000). Frames
// are BGR from the decoder, converted to options.color_mode.
//
// Failure: a missing file or one no backend can open throws std::runtime_error from the
// constructor; a frame whose time does not increase throws std::invalid_argument from Next()
// (pass --fps). Decoders cannot tell a truncated file from its end, so a stream that ends before
// the frame count the container announces is reported at that point: std::runtime_error, or with
// skip_bad_frames one SkippedFrames() entry for the missing frames. (Containers that only estimate
// their count could over-announce; skip_bad_frames then turns the error into a recorded warning.)
#include <filesystem>
#include <string>

#include <opencv2/videoio.hpp>

#include "perception/io/frame_source.h"

namespace aperture::perception {

class VideoFileSource : public FrameSource {
 public:
  VideoFileSource(const std::filesystem::path& path, const FrameSourceOptions& options);

  std::optional<Frame> Next() override;
  std::string Describe() const override;
  // Frame count from the container (CAP_PROP_FRAME_COUNT), nullopt when it does not say.
  std::optional<size_t> SizeHint() const override { return frame_count_; }

 private:
  std::filesystem::path path_;
  FrameSourceOptions options_;
  cv::VideoCapture capture_;
  std::optional<size_t> frame_count_;
  int next_index_ = 0;
  double last_t_s_ = 0.0;
  bool ended_ = false;
};

}  // namespace aperture::perception
