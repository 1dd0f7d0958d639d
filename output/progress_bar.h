#pragma once
// ProgressBar: one self-overwriting status line on stderr for long runs, e.g.
//   "sim [##########..........]   512/1000  98.3/s  ETA 0:05"
// It draws only when stderr is a terminal (isatty), so logs, pipes and ctest stay clean. Redraws
// are throttled (at most every 100 ms) so per-frame Update() calls cost next to nothing.
//
//   ProgressBar progress("frames", frame_count);
//   for (...) { ...; progress.Update(i + 1); }
//   progress.Finish();   // final state + newline (also done by the destructor)
#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace aperture::output {

class ProgressBar {
 public:
  // total 0 = unknown (no bar, no ETA). Writes to std::cerr when stderr is a terminal.
  ProgressBar(std::string label, std::size_t total);
  // For tests and custom sinks: `enabled` false draws nothing.
  ProgressBar(std::string label, std::size_t total, std::ostream& out, bool enabled);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void Update(std::size_t done);
  void Increment() { Update(done_ + 1); }
  // Draws the final state and ends the line. Idempotent.
  void Finish();

  bool enabled() const { return enabled_; }
  // The line as it would be drawn now (without the carriage return).
  std::string Line() const;

 private:
  void Draw();

  std::string label_;
  std::size_t total_;
  std::ostream& out_;
  bool enabled_;
  bool finished_ = false;
  bool drawn_ = false;
  std::size_t done_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace aperture::output
