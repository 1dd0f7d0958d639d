#pragma once
// BackgroundVideoWriter: a VideoWriter (output/video_writer.h) whose encoding runs on its own
// thread, so a simulation loop is not held up by the codec (mp4v of a 1392 x 480 frame costs
// ~5 ms). Frames are encoded in the order written, exactly as VideoWriter would; at most
// kMaxQueuedFrames wait, beyond that Write blocks until the encoder catches up (bounded memory).
// An encoder error (bad frame size, no codec) stops the encoding and is rethrown by every later
// Write and by Close; Write after Close throws std::logic_error.
//
//   BackgroundVideoWriter video(out.Path("sim"), 30.0);
//   video.Write(frame);   // shares frame's pixels: do not modify them afterwards
//   std::optional<std::string> file = video.Close();   // waits for the encoder
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <thread>

#include "output/video_writer.h"

namespace aperture::output {

class BackgroundVideoWriter {
 public:
  static constexpr std::size_t kMaxQueuedFrames = 8;

  // std::invalid_argument for fps_hz <= 0 or non-finite (VideoWriter).
  BackgroundVideoWriter(std::string path_stem, double fps_hz,
                        VideoFormat format = VideoFormat::kMp4OrAvi);
  ~BackgroundVideoWriter();  // finishes the video like Close, swallowing errors
  BackgroundVideoWriter(const BackgroundVideoWriter&) = delete;
  BackgroundVideoWriter& operator=(const BackgroundVideoWriter&) = delete;

  // Queues `frame` (8-bit, 1 or 3 channels, the first frame's size and type).
  void Write(const cv::Mat& frame);
  // Encodes what is queued, finishes the file; VideoWriter::Close's result. Idempotent.
  std::optional<std::string> Close();

 private:
  void Encode();
  void RethrowEncoderError() const;  // with mutex_ held

  VideoWriter writer_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<cv::Mat> queue_;
  bool closed_ = false;
  std::exception_ptr error_;  // the encoder's first error; it stops encoding
  std::optional<std::string> result_;
  std::thread encoder_;  // last: starts after the members above exist
};

}  // namespace aperture::output
