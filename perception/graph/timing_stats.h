#pragma once
// Summary statistics of measured durations, for the "timing" table of summary.json.
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

struct NodeTiming {
  std::string node;
  TimingStats stats;
};

}  // namespace aperture::perception
