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
// (pass --fps). The end of the decodable stream ends the source: a video cut short ends early
// rather than reporting a bad frame (decoders do not distinguish the two).
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
};

}  // namespace aperture::perception
