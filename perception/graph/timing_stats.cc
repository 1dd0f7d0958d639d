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

}  // namespace aperture::perception
