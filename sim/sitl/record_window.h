#pragma once
// Keeps a time-ordered record (anything with a `t_s` member, e.g. control::QuadState,
// perception::ImuSample) to its last window_s of simulated time, so a long flight's records stay
// bounded (SitlRunnerParams::record_window_s). The records older than t_s - window_s are dropped
// once the oldest is more than two windows old: one erase per window, amortized O(1) per record,
// and at most about two windows kept (the vector's capacity stops growing with them).
//
//   KeepLastWindow(&result.imu, t_s, params.record_window_s);   // after each push_back
#include <algorithm>
#include <vector>

namespace aperture::sim {

// window_s <= 0 keeps everything.
template <typename Record>
void KeepLastWindow(std::vector<Record>* records, double t_s, double window_s) {
  if (window_s <= 0.0 || records->empty() || records->front().t_s >= t_s - 2.0 * window_s) return;
  const auto first_kept =
      std::lower_bound(records->begin(), records->end(), t_s - window_s,
                       [](const Record& record, double t) { return record.t_s < t; });
  records->erase(records->begin(), first_kept);
}

}  // namespace aperture::sim
