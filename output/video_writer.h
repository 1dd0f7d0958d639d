#pragma once
// VideoWriter: an overlay video in the output folder, opened on the first frame (size and colour
// taken from it). It tries MPEG-4 Part 2 ('mp4v') in "<stem>.mp4" first and falls back to Motion
// JPEG ('MJPG') in "<stem>.avi" when the OpenCV build cannot open that. On Debian 12 (OpenCV 4.6
// with its FFmpeg backend) both work; tests write and read back each. Frames go to
// "<stem>.partial.<ext>", renamed on Close(), so an interrupted run leaves no video that looks
// complete.
//
//   VideoWriter video(out.Path("overlay"), 30.0);
//   video.Write(overlay_bgr);                    // every frame; same size as the first
//   std::optional<std::string> file = video.Close();   // "…/overlay.mp4", nullopt without frames
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>

namespace cv {
class VideoWriter;
}

namespace aperture::output {

enum class VideoFormat {
  kMp4OrAvi,  // mp4v/.mp4, falling back to MJPG/.avi
  kAvi,       // MJPG/.avi only: frame-exact JPEG frames, larger files
};

class VideoWriter {
 public:
  // std::invalid_argument for fps_hz <= 0 or non-finite.
  VideoWriter(std::string path_stem, double fps_hz, VideoFormat format = VideoFormat::kMp4OrAvi);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // 8-bit, 1 or 3 channels (grey is converted to BGR). std::invalid_argument when the size or type
  // differs from the first frame; std::runtime_error when no codec can be opened.
  void Write(const cv::Mat& frame);
  // Finishes the file and renames it into place. Idempotent; returns the final path.
  std::optional<std::string> Close();

  // "mp4v" or "MJPG" once the first frame was written, "" before.
  const std::string& codec() const { return codec_; }
  std::size_t frames_written() const { return frames_written_; }

 private:
  void Open(const cv::Mat& first_frame);
  void Discard();

  std::string path_stem_;
  double fps_hz_;
  VideoFormat format_;
  std::unique_ptr<cv::VideoWriter> writer_;
  std::string codec_;
  std::string partial_path_, final_path_;
  cv::Size frame_size_;
  std::size_t frames_written_ = 0;
  bool closed_ = false;
  int uncaught_exceptions_at_open_;
};

}  // namespace aperture::output
