#pragma once
// FrameSource: the one interface every image producer implements (image folder, video file,
// camera device, in-process simulator queue), so front ends and `aperture run` do not care where
// frames come from.
//
// Contract:
//  - Next() returns frames in capture order with strictly increasing Frame::t_s (seconds on the
//    source's clock, see each implementation) and images of one size, type CV_8UC1 (gray) or
//    CV_8UC3 (BGR) as chosen by FrameSourceOptions::color_mode; nullopt at the end.
//  - Frame::index is the position of the frame in its source (file order for folders, frame
//    number for videos), so a skipped frame leaves a gap. Frame::camera_id is options.camera_id.
//  - Bad input throws std::runtime_error (I/O: unreadable, corrupt, truncated) or
//    std::invalid_argument (inconsistent: wrong size, bad timestamps) naming the file and the fix.
//    With skip_bad_frames, a bad *frame* (corrupt, truncated, wrong size) is instead skipped,
//    recorded in SkippedFrames() and reported as one "warning:" line on stderr; it is never
//    dropped silently. Errors of the whole sequence (missing folder, bad timestamps) always throw.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "perception/sensor_data.h"

namespace aperture::perception {

enum class ColorMode {
  kGray,   // CV_8UC1
  kColor,  // CV_8UC3, BGR channel order (OpenCV convention)
};

struct FrameSourceOptions {
  ColorMode color_mode = ColorMode::kGray;  // most front ends work on gray images
  // Frame rate [Hz] used to time frames as t_i = index / fps. 0 = unset. Image folders use it only
  // when they carry no times (times.txt, data.csv, timestamp file names); videos use it instead
  // of the container's timestamps (for files with broken timestamps); cameras ignore it.
  double fps = 0.0;
  // Skip (and record) corrupt, truncated or wrong-size frames instead of throwing.
  bool skip_bad_frames = false;
  int camera_id = 0;  // copied into Frame::camera_id
  // ROS bags only (rosbag_source.h): the sensor_msgs/Image or CompressedImage topic to read
  // (required for a bag) and an optional sensor_msgs/Imu topic ("" = none).
  std::string image_topic;
  std::string imu_topic;
};

// A frame the source left out, and why.
struct SkippedFrame {
  std::string item;    // file path, or "frame <index>" for streams
  std::string reason;  // what was wrong
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;

  // Next frame, or nullopt at the end of the source. May block (cameras, in-process queues).
  virtual std::optional<Frame> Next() = 0;
  // One line for logs and reports, e.g. "image folder 'seq/' (120 images, times from times.txt)".
  virtual std::string Describe() const = 0;
  // Total number of frames when known in advance (for a progress bar), including frames that may
  // still turn out to be bad; nullopt for live or open-ended sources.
  virtual std::optional<size_t> SizeHint() const = 0;

  const std::vector<SkippedFrame>& SkippedFrames() const { return skipped_; }

  // IMU samples the source recorded up to the frame Next() returned last, oldest first, each
  // returned once (a ROS bag with an IMU topic); empty for sources without an IMU.
  virtual std::vector<ImuSample> TakeImuSamples() { return {}; }

 protected:
  // Records a skipped frame and prints "warning: <source>: skipping <item>: <reason>" to stderr.
  void RecordSkip(const std::string& item, const std::string& reason);

 private:
  std::vector<SkippedFrame> skipped_;
};

// Throws std::invalid_argument unless options.fps is 0 (unset) or a finite positive rate.
void CheckFrameSourceOptions(const FrameSourceOptions& options);

// Converts an 8-bit 1-, 3- or 4-channel (BGR/BGRA) image to the type `mode` asks for; returns the
// input unchanged (no copy) when it already matches. Throws std::invalid_argument for other types.
cv::Mat ConvertToColorMode(const cv::Mat& image, ColorMode mode);

// "gray" or "color".
std::string ToString(ColorMode mode);

}  // namespace aperture::perception
