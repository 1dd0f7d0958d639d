#include "perception/io/in_process_source.h"

#include <sstream>
#include <stdexcept>
#include <utility>

namespace aperture::perception {

InProcessSource::InProcessSource(const FrameSourceOptions& options, std::string name)
    : options_(options), name_(std::move(name)) {}

void InProcessSource::Push(Frame frame) {
  if (frame.image.empty() || frame.image.depth() != CV_8U ||
      (frame.image.channels() != 1 && frame.image.channels() != 3 &&
       frame.image.channels() != 4)) {
    throw std::invalid_argument(name_ + ": pushed frame " + std::to_string(frame.index) +
                                " has an empty or non-8-bit gray/BGR/BGRA image; render CV_8UC1 "
                                "or CV_8UC3");
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (closed_) {
    throw std::logic_error(name_ + ": Push() after Close(); stop the producer before closing");
  }
  if (any_pushed_ && !(frame.t_s > last_pushed_t_s_)) {
    std::ostringstream message;
    message.precision(17);
    message << name_ << ": pushed frame " << frame.index << " has t = " << frame.t_s
            << " s, not after the previous frame's " << last_pushed_t_s_
            << " s; push frames in time order with distinct timestamps";
    throw std::invalid_argument(message.str());
  }
  if (any_pushed_ && frame.image.size() != frame_size_) {
    throw std::invalid_argument(name_ + ": pushed frame " + std::to_string(frame.index) +
                                " changes the image size; all frames must have one size");
  }
  any_pushed_ = true;
  last_pushed_t_s_ = frame.t_s;
  frame_size_ = frame.image.size();
  queue_.push_back(std::move(frame));
  frame_or_close_.notify_one();
}

void InProcessSource::Close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  frame_or_close_.notify_all();
}

std::optional<Frame> InProcessSource::Next() {
  std::unique_lock<std::mutex> lock(mutex_);
  frame_or_close_.wait(lock, [this] { return !queue_.empty() || closed_; });
  if (queue_.empty()) return std::nullopt;
  Frame frame = std::move(queue_.front());
  queue_.pop_front();
  lock.unlock();
  frame.image = ConvertToColorMode(frame.image, options_.color_mode);
  return frame;
}

}  // namespace aperture::perception
