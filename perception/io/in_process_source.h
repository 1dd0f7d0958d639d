#pragma once
// InProcessSource: a thread-safe frame queue that a producer in the same process (the simulator's
// renderer, a ROS callback) pushes frames into and a consumer reads as a FrameSource.
//
// Frames keep the producer's t_s, index and camera_id; their images are converted to
// options.color_mode on the consumer side. Push() checks what the producer sends: a non-empty
// 8-bit gray/BGR/BGRA image, strictly increasing t_s, one image size; it throws
// std::invalid_argument otherwise (in the producer's thread, where the bug is), and
// std::logic_error after Close(). The queue is unbounded: a producer that outruns the consumer
// grows memory (lockstep SITL pushes one frame per step).
#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>

#include <opencv2/core/types.hpp>

#include "perception/io/frame_source.h"

namespace aperture::perception {

class InProcessSource : public FrameSource {
 public:
  explicit InProcessSource(const FrameSourceOptions& options = {},
                           std::string name = "in-process source");

  // Thread-safe. Enqueues a frame; throws as described above.
  void Push(Frame frame);
  // Thread-safe. Ends the source: Next() returns the frames already queued, then nullopt.
  void Close();

  // Blocks until a frame is queued or the source is closed.
  std::optional<Frame> Next() override;
  std::string Describe() const override { return name_; }
  std::optional<size_t> SizeHint() const override { return std::nullopt; }

 private:
  FrameSourceOptions options_;
  std::string name_;
  std::mutex mutex_;
  std::condition_variable frame_or_close_;
  std::deque<Frame> queue_;
  bool closed_ = false;
  bool any_pushed_ = false;
  double last_pushed_t_s_ = 0.0;
  cv::Size frame_size_;
};

}  // namespace aperture::perception
