#pragma once
// Fixed-rate sampling on the simulator clock, shared by the simulated sensors. The first call of
// Due() samples; afterwards a sample is due once t reaches the next slot of the nominal grid
// t_first + k / rate_hz (so the rate does not drift when the caller's steps do not divide the
// period). Slots the caller stepped over are skipped, not back-filled: call at least at rate_hz.
#include <cmath>

namespace aperture::sim {

class SampleSchedule {
 public:
  explicit SampleSchedule(double rate_hz) : period_s_(1.0 / rate_hz) {}

  double period_s() const { return period_s_; }

  // True when a sample is due at t_s (non-decreasing across calls); then advances the grid.
  bool Due(double t_s) {
    // Rounding of accumulated simulator time must not push a slot to the next call.
    const double tolerance_s = 1e-6 * period_s_;
    if (!started_) {
      started_ = true;
      next_s_ = t_s + period_s_;
      return true;
    }
    if (t_s < next_s_ - tolerance_s) return false;
    next_s_ += period_s_ * std::floor((t_s - next_s_ + tolerance_s) / period_s_ + 1.0);
    return true;
  }

 private:
  double period_s_;
  double next_s_ = 0.0;
  bool started_ = false;
};

}  // namespace aperture::sim
