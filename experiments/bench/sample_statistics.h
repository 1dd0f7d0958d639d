#pragma once
// Summary figures of a bench's samples, one definition for every bench: an empty sample has no
// figure (NaN), which FiniteOrNull writes as null (JSON has no NaN).
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <vector>

namespace aperture::experiments {

// Arithmetic mean; NaN for no samples.
inline double Mean(const std::vector<double>& values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

// Population standard deviation (divides by n: the spread of the sample itself, as the papers'
// tables report it); NaN for no samples.
inline double StandardDeviation(const std::vector<double>& values) {
  const double mean = Mean(values);
  double sum = 0.0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return values.empty() ? mean : std::sqrt(sum / static_cast<double>(values.size()));
}

// The sorted sample's element n/2 (for an even n the upper of the two middle ones, not their
// mean); NaN for no samples.
inline double UpperMedian(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The value, or null when it is NaN or infinite.
inline nlohmann::json FiniteOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace aperture::experiments
