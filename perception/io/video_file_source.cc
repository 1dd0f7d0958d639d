#include "perception/io/video_file_source.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace aperture::perception {

VideoFileSource::VideoFileSource(const std::filesystem::path& path,
                                 const FrameSourceOptions& options)
    : path_(path), options_(options) {
  CheckFrameSourceOptions(options);
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error("video file '" + path.string() +
                             "' does not exist; check the path given as the frame source");
  }
  if (!std::filesystem::is_regular_file(path)) {
    throw std::invalid_argument("'" + path.string() +
                                "' is not a regular file (a device, FIFO or socket); give an "
                                "image folder, a video file, a ROS bag or camera:<N>");
  }
  if (!capture_.open(path.string(), cv::CAP_ANY) || !capture_.isOpened()) {
    throw std::runtime_error("cannot open video file '" + path.string() +
                             "' with OpenCV (unsupported container or codec); convert it, e.g. "
                             "'ffmpeg -i <in> -c:v mjpeg out.avi', or extract its frames into a "
                             "folder");
  }
  const double count = capture_.get(cv::CAP_PROP_FRAME_COUNT);
  if (std::isfinite(count) && count > 0.0) frame_count_ = static_cast<size_t>(std::llround(count));
}

std::optional<Frame> VideoFileSource::Next() {
  if (ended_) return std::nullopt;
  cv::Mat image;
  if (!capture_.read(image) || image.empty()) {
    ended_ = true;
    const size_t delivered = static_cast<size_t>(next_index_);
    if (frame_count_ && delivered < *frame_count_) {
      const std::string reason = "video ended after " + std::to_string(delivered) + " of the " +
                                 std::to_string(*frame_count_) +
                                 " frames its container announces (truncated or corrupt file)";
      if (!options_.skip_bad_frames) {
        throw std::runtime_error("video file '" + path_.string() + "': " + reason +
                                 "; re-copy or re-encode it, or pass --skip-bad-frames to accept "
                                 "the frames that decode");
      }
      RecordSkip("frames " + std::to_string(delivered) + ".." + std::to_string(*frame_count_ - 1),
                 reason);
    }
    return std::nullopt;
  }
  Frame frame;
  frame.index = next_index_++;
  frame.camera_id = options_.camera_id;
  frame.t_s =
      options_.fps > 0.0 ? frame.index / options_.fps : capture_.get(cv::CAP_PROP_POS_MSEC) * 1e-3;
  if (frame.index > 0 && !(frame.t_s > last_t_s_)) {
    std::ostringstream message;
    message.precision(17);
    message << "video file '" << path_.string() << "': frame " << frame.index << " has time "
            << frame.t_s << " s, not after frame " << frame.index - 1 << " (" << last_t_s_
            << " s); the container timestamps are broken, pass --fps to time frames by rate";
    throw std::invalid_argument(message.str());
  }
  last_t_s_ = frame.t_s;
  frame.image = ConvertToColorMode(image, options_.color_mode);
  return frame;
}

std::string VideoFileSource::Describe() const {
  std::string text = "video file '" + path_.string() + "' (" + capture_.getBackendName() + ", " +
                     ToString(options_.color_mode);
  if (frame_count_) text += ", " + std::to_string(*frame_count_) + " frames";
  return text + ")";
}

}  // namespace aperture::perception
