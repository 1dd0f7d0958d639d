#include "output/background_video_writer.h"

#include <stdexcept>
#include <utility>

namespace aperture::output {

BackgroundVideoWriter::BackgroundVideoWriter(std::string path_stem, double fps_hz,
                                             VideoFormat format)
    : writer_(std::move(path_stem), fps_hz, format), encoder_([this] { Encode(); }) {}

BackgroundVideoWriter::~BackgroundVideoWriter() {
  try {
    Close();
  } catch (...) {  // a destructor must not throw; Close reports errors to callers that ask
  }
}

void BackgroundVideoWriter::Encode() {
  for (;;) {
    cv::Mat frame;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return !queue_.empty() || closed_; });
      if (queue_.empty()) return;  // closed, all encoded
      frame = std::move(queue_.front());
      queue_.pop_front();
    }
    changed_.notify_all();  // room in the queue
    try {
      writer_.Write(frame);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      queue_.clear();
      changed_.notify_all();
      return;
    }
  }
}

void BackgroundVideoWriter::RethrowEncoderError() const {
  if (error_) std::rethrow_exception(error_);
}

void BackgroundVideoWriter::Write(const cv::Mat& frame) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (closed_) throw std::logic_error("BackgroundVideoWriter::Write after Close");
  changed_.wait(lock, [this] { return queue_.size() < kMaxQueuedFrames || error_ != nullptr; });
  RethrowEncoderError();
  queue_.push_back(frame);
  lock.unlock();
  changed_.notify_all();
}

std::optional<std::string> BackgroundVideoWriter::Close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
  if (encoder_.joinable()) {
    encoder_.join();
    result_ = writer_.Close();
  }
  std::lock_guard<std::mutex> lock(mutex_);
  RethrowEncoderError();
  return result_;
}

}  // namespace aperture::output
