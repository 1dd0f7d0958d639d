#include "output/video_writer.h"

#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace aperture::output {

VideoWriter::VideoWriter(std::string path_stem, double fps_hz, VideoFormat format)
    : path_stem_(std::move(path_stem)),
      fps_hz_(fps_hz),
      format_(format),
      uncaught_exceptions_at_open_(std::uncaught_exceptions()) {
  if (!(std::isfinite(fps_hz) && fps_hz > 0)) {
    throw std::invalid_argument("video '" + path_stem_ + "': frame rate " + std::to_string(fps_hz) +
                                " Hz must be positive");
  }
}

VideoWriter::~VideoWriter() {
  if (std::uncaught_exceptions() > uncaught_exceptions_at_open_) {
    Discard();
    return;
  }
  try {
    Close();
  } catch (const std::exception& e) {
    std::cerr << "aperture: " << e.what() << "\n";
    Discard();
  }
}

void VideoWriter::Open(const cv::Mat& first_frame) {
  frame_size_ = first_frame.size();
  struct Choice {
    const char* codec;
    const char* extension;
  };
  // mp4 plays everywhere; MJPG/avi is the container every OpenCV build can write.
  std::vector<Choice> choices = {Choice{"mp4v", ".mp4"}, Choice{"MJPG", ".avi"}};
  if (format_ == VideoFormat::kAvi) choices.erase(choices.begin());
  for (const Choice& choice : choices) {
    const std::string partial = path_stem_ + ".partial" + choice.extension;
    auto writer = std::make_unique<cv::VideoWriter>();
    const std::string& c = choice.codec;
    if (writer->open(partial, cv::VideoWriter::fourcc(c[0], c[1], c[2], c[3]), fps_hz_, frame_size_,
                     true) &&
        writer->isOpened()) {
      writer_ = std::move(writer);
      codec_ = choice.codec;
      partial_path_ = partial;
      final_path_ = path_stem_ + choice.extension;
      return;
    }
    std::error_code ignored;  // a failed open may leave an empty file behind
    std::filesystem::remove(partial, ignored);
  }
  throw std::runtime_error("cannot open a video writer for '" + path_stem_ + "' (" +
                           (format_ == VideoFormat::kAvi ? "MJPG .avi" : "mp4v .mp4 or MJPG .avi") +
                           "): no such encoder in this OpenCV build, or the folder is not "
                           "writable");
}

void VideoWriter::Write(const cv::Mat& frame) {
  if (closed_) throw std::logic_error("video '" + path_stem_ + "': Write after Close");
  if (frame.empty() || frame.depth() != CV_8U || (frame.channels() != 1 && frame.channels() != 3)) {
    throw std::invalid_argument("video '" + path_stem_ + "': frame " +
                                std::to_string(frames_written_) +
                                " must be a non-empty 8-bit grey or BGR image");
  }
  if (!writer_) Open(frame);
  if (frame.size() != frame_size_) {
    throw std::invalid_argument("video '" + path_stem_ + "': frame " +
                                std::to_string(frames_written_) + " is " +
                                std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                                " but the video is " + std::to_string(frame_size_.width) + "x" +
                                std::to_string(frame_size_.height) + "; resize overlays first");
  }
  if (frame.channels() == 1) {
    cv::Mat bgr;
    cv::cvtColor(frame, bgr, cv::COLOR_GRAY2BGR);
    writer_->write(bgr);
  } else {
    writer_->write(frame);
  }
  ++frames_written_;
}

std::optional<std::string> VideoWriter::Close() {
  if (closed_) return writer_ ? std::optional<std::string>(final_path_) : std::nullopt;
  closed_ = true;
  if (!writer_) return std::nullopt;
  writer_->release();
  std::error_code error;
  std::filesystem::rename(partial_path_, final_path_, error);
  if (error) {
    throw std::runtime_error("cannot rename '" + partial_path_ + "' to '" + final_path_ +
                             "': " + error.message());
  }
  return final_path_;
}

void VideoWriter::Discard() {
  if (closed_) return;
  closed_ = true;
  if (!writer_) return;
  writer_->release();
  std::error_code ignored;
  std::filesystem::remove(partial_path_, ignored);
  writer_.reset();
}

}  // namespace aperture::output
