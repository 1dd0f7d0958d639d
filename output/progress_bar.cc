#include "output/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace aperture::output {
namespace {

constexpr std::chrono::milliseconds kRedrawInterval(100);  // 10 Hz reads as smooth
constexpr int kBarWidth = 24;

std::string FormatDuration(double seconds) {
  const long total = std::lround(seconds);
  char buffer[32];
  if (total >= 3600) {
    std::snprintf(buffer, sizeof(buffer), "%ld:%02ld:%02ld", total / 3600, total / 60 % 60,
                  total % 60);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%ld:%02ld", total / 60, total % 60);
  }
  return buffer;
}

}  // namespace

ProgressBar::ProgressBar(std::string label, std::size_t total)
    : ProgressBar(std::move(label), total, std::cerr, isatty(STDERR_FILENO) == 1) {}

ProgressBar::ProgressBar(std::string label, std::size_t total, std::ostream& out, bool enabled)
    : label_(std::move(label)),
      total_(total),
      out_(out),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { Finish(); }

void ProgressBar::Update(std::size_t done) {
  done_ = done;
  if (!enabled_ || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_draw_ < kRedrawInterval && !(total_ > 0 && done_ >= total_)) return;
  last_draw_ = now;
  Draw();
}

void ProgressBar::Finish() {
  if (finished_) return;
  if (enabled_) {
    Draw();
    out_ << '\n' << std::flush;
  }
  finished_ = true;
}

std::string ProgressBar::Line() const {
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed_s > 0 ? static_cast<double>(done_) / elapsed_s : 0.0;
  char numbers[96];
  std::string line = label_;
  if (total_ > 0) {
    const double fraction = std::min(1.0, static_cast<double>(done_) / total_);
    const int filled = static_cast<int>(fraction * kBarWidth);
    line += " [" + std::string(filled, '#') + std::string(kBarWidth - filled, '.') + "]";
    std::snprintf(numbers, sizeof(numbers), " %zu/%zu  %.1f/s", done_, total_, rate);
    line += numbers;
    if (rate > 0 && done_ < total_) {
      line += "  ETA " + FormatDuration(static_cast<double>(total_ - done_) / rate);
    } else if (done_ >= total_) {
      line += "  " + FormatDuration(elapsed_s);
    }
  } else {
    std::snprintf(numbers, sizeof(numbers), " %zu  %.1f/s", done_, rate);
    line += numbers;
  }
  return line;
}

void ProgressBar::Draw() {
  // "\r" returns to the line start, "\033[K" clears what a longer previous line left behind.
  out_ << '\r' << Line() << "\033[K" << std::flush;
  drawn_ = true;
}

}  // namespace aperture::output
