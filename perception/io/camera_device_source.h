#pragma once
// CameraDeviceSource: live frames from a camera device (cv::VideoCapture by index, e.g. V4L2
// /dev/video<N> on Linux).
//
// Timestamps [s]: std::chrono::steady_clock time (since its epoch) taken right after the grab
// returns, so frames can be aligned with other sensors stamped on the same clock. Exposure and
// transfer latency are not compensated. options.fps is ignored.
//
// Failure: a device that cannot be opened throws std::runtime_error from the constructor naming
// the index; a device that stops delivering frames throws std::runtime_error from Next().
#include <string>

#include <opencv2/videoio.hpp>

#include "perception/io/frame_source.h"

namespace aperture::perception {

class CameraDeviceSource : public FrameSource {
 public:
  CameraDeviceSource(int device_index, const FrameSourceOptions& options);

  // Blocks until the device delivers the next frame. Never returns nullopt.
  std::optional<Frame> Next() override;
  std::string Describe() const override;
  std::optional<size_t> SizeHint() const override { return std::nullopt; }

 private:
  int device_index_;
  FrameSourceOptions options_;
  cv::VideoCapture capture_;
  int next_index_ = 0;
};

}  // namespace aperture::perception
