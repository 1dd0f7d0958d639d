#include "perception/io/camera_device_source.h"

#include <chrono>
#include <stdexcept>

namespace aperture::perception {

CameraDeviceSource::CameraDeviceSource(int device_index, const FrameSourceOptions& options)
    : device_index_(device_index), options_(options) {
  CheckFrameSourceOptions(options);
  if (device_index < 0) {
    throw std::invalid_argument("camera index " + std::to_string(device_index) +
                                " is negative; use camera:0 for the first camera");
  }
  if (!capture_.open(device_index, cv::CAP_ANY) || !capture_.isOpened()) {
    throw std::runtime_error("cannot open camera:" + std::to_string(device_index) +
                             " (no such device, or it is busy); list cameras with "
                             "'ls /dev/video*' or 'v4l2-ctl --list-devices' and pass camera:<N>");
  }
}

std::optional<Frame> CameraDeviceSource::Next() {
  Frame frame;
  cv::Mat image;
  const bool grabbed = capture_.grab();
  frame.t_s = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
                  .count();
  if (!grabbed || !capture_.retrieve(image) || image.empty()) {
    throw std::runtime_error(Describe() + " stopped delivering frames after " +
                             std::to_string(next_index_) +
                             " frames; check the cable and that no other program uses it");
  }
  frame.index = next_index_++;
  frame.camera_id = options_.camera_id;
  frame.image = ConvertToColorMode(image, options_.color_mode);
  return frame;
}

std::string CameraDeviceSource::Describe() const {
  return "camera:" + std::to_string(device_index_) + " (" + ToString(options_.color_mode) + ")";
}

}  // namespace aperture::perception
