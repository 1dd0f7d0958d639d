#include "perception/graph/timing_stats.h"

#include <algorithm>
#include <cmath>

namespace aperture::perception {
namespace {

// `sorted` must be non-empty and ascending; fraction in [0, 1].
double Percentile(const std::vector<double>& sorted, double fraction) {
  const double position = fraction * static_cast<double>(sorted.size() - 1);
  const std::size_t below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  const double weight = position - static_cast<double>(below);
  return sorted[below] + weight * (sorted[above] - sorted[below]);
}

}  // namespace

TimingStats SummarizeDurations(std::vector<double> durations_s) {
  TimingStats stats;
  stats.count = static_cast<int>(durations_s.size());
  if (durations_s.empty()) return stats;
  std::sort(durations_s.begin(), durations_s.end());
  stats.median_s = Percentile(durations_s, 0.5);
  stats.p95_s = Percentile(durations_s, 0.95);
  stats.max_s = durations_s.back();
  return stats;
}

void DurationRecord::Add(double duration_s) {
  const bool kept = count_ % stride_ == 0;
  max_s_ = count_ == 0 ? duration_s : std::max(max_s_, duration_s);
  ++count_;
  if (!kept) return;
  kept_s_.push_back(duration_s);
  if (kept_s_.size() < kMaxKept) return;
  // Keep indices 0, 2 stride, 4 stride, ...: the kept ones of twice the stride.
  std::size_t out = 0;
  for (std::size_t i = 0; i < kept_s_.size(); i += 2) kept_s_[out++] = kept_s_[i];
  kept_s_.resize(out);
  stride_ *= 2;
}

TimingStats DurationRecord::Summary() const {
  TimingStats stats = SummarizeDurations(kept_s_);
  stats.count = count_;
  stats.max_s = max_s_;
  return stats;
}

}  // namespace aperture::perception
