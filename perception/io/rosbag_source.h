#pragma once
// RosbagSource: frames (and IMU samples) of a ROS1 bag, read with Debian's rosbag storage library,
// so the datasets people own (EuRoC, UZH-FPV, TUM-VI, Blackbird) replay through `aperture run`.
//
//   aperture run --source flight.bag --image-topic /cam0/image_raw [--imu-topic /imu0]
//
// Messages: sensor_msgs/Image with encoding mono8, bgr8, rgb8, bgra8 or rgba8 (8UC1/8UC3 as
// mono8/bgr8), or sensor_msgs/CompressedImage (any format cv::imdecode reads: jpeg, png);
// sensor_msgs/Imu (linear_acceleration -> specific_force_B, angular_velocity -> omega_B, in the
// IMU's frame, which aperture takes as B). Frames come in bag order (the order the recorder
// received them) with Frame::t_s = header.stamp [s] (the bag's receive time where the stamp is
// zero), Frame::index = position on the image topic, images converted to options.color_mode.
//
// Failure: an unreadable bag throws std::runtime_error; a missing topic, a topic of another type
// (both naming the bag's topics and types) and an unknown encoding throw std::invalid_argument; so
// does a frame time that does not increase. With skip_bad_frames, an image that cannot be decoded
// or does not match the first frame's size is skipped and recorded instead.
#include <deque>
#include <filesystem>
#include <memory>
#include <string>

#include "perception/camera/calibration_io.h"
#include "perception/io/frame_source.h"

namespace aperture::perception {

class RosbagSource : public FrameSource {
 public:
  // options.image_topic is required; options.imu_topic optional.
  RosbagSource(const std::filesystem::path& path, const FrameSourceOptions& options);
  ~RosbagSource() override;

  std::optional<Frame> Next() override;
  std::string Describe() const override;
  std::optional<size_t> SizeHint() const override { return image_count_; }
  std::vector<ImuSample> TakeImuSamples() override;

 private:
  struct Reader;  // the bag and its view (keeps ROS headers out of this header)
  std::filesystem::path path_;
  FrameSourceOptions options_;
  std::unique_ptr<Reader> reader_;
  size_t image_count_ = 0;
  size_t imu_count_ = 0;
  std::string image_type_;
  int next_index_ = 0;
  double last_t_s_ = 0.0;
  int width_ = 0, height_ = 0;
  std::vector<ImuSample> imu_;
};

// The camera of the first sensor_msgs/CameraInfo message on `topic` of the bag at `path`
// (distortion_model plumb_bob -> radtan, equidistant -> equidistant, none or all-zero -> pinhole).
// Throws std::invalid_argument naming the bag and the topic when the topic is missing, empty or
// of another type, or the message describes a camera aperture has no model for.
CameraCalibration LoadCameraInfoFromBag(const std::filesystem::path& path,
                                        const std::string& topic);

}  // namespace aperture::perception
