#pragma once
// Summary statistics of measured durations, for the "timing" table of summary.json.
#include <cstddef>
#include <string>
#include <vector>

namespace aperture::perception {

struct TimingStats {
  int count = 0;
  double median_s = 0.0;  // all zero when count == 0
  double p95_s = 0.0;
  double max_s = 0.0;
};

// Median and 95th percentile by linear interpolation between order statistics (the "linear"
// method of numpy.percentile), so median_s <= p95_s <= max_s always holds.
TimingStats SummarizeDurations(std::vector<double> durations_s);

// The durations of a run, in memory that stays flat however long it runs (a node's per-frame
// times over an hour of flight, aperture bench soak): every duration until kMaxKept are kept,
// then every 2nd, then every 4th, ... so the kept ones stay evenly spread over the run. Summary():
// count and max over every duration, median and p95 over the kept ones (all of them for runs of
// fewer than kMaxKept).
class DurationRecord {
 public:
  static constexpr std::size_t kMaxKept = 8192;  // 64 kB

  void Add(double duration_s);
  TimingStats Summary() const;
  std::size_t kept() const { return kept_s_.size(); }

 private:
  std::vector<double> kept_s_;  // the durations of index 0, stride, 2 stride, ...
  std::size_t stride_ = 1;
  int count_ = 0;
  double max_s_ = 0.0;
};

struct NodeTiming {
  std::string node;
  TimingStats stats;
};

}  // namespace aperture::perception
