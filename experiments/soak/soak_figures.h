#pragma once
// The verdict of aperture bench soak from its samples (soak_sampler.h): memory growth after the
// warm-up and the drift of the per-frame cost from the first to the last window of the run.
//
//   rss_growth_percent = 100 (RSS_end - RSS_ref) / RSS_ref, RSS_ref at the first sample at or after
//                        rss_reference_s (issue 18: minute 1), RSS_end at the last sample;
//   frame_*_median_ms first / last = the median of the interval medians of the samples stamped in
//                        [0, timing_window_s] / (t_end - timing_window_s, t_end] (issue 18: the
//                        first and last ten minutes);
//   frame_*_drift_percent = 100 (last - first) / first.
// The check: rss_growth_percent < max_rss_growth_percent (5 %).
#include <nlohmann/json.hpp>
#include <vector>

#include "experiments/soak/soak_sampler.h"

namespace aperture::experiments {

struct SoakCheckParams {
  double rss_reference_s = 60.0;   // minute 1
  double timing_window_s = 600.0;  // ten minutes
  double max_rss_growth_percent = 5.0;
};

// The windows, shrunk for a run shorter than them: the reference at min(60 s,
// duration / 2), the timing windows min(600 s, duration / 2) long.
SoakCheckParams SoakCheckParamsFor(double duration_s);

struct SoakFigures {
  SoakCheckParams check;
  double rss_reference_t_s = 0.0;
  double rss_reference_mib = 0.0;
  double rss_end_t_s = 0.0;
  double rss_end_mib = 0.0;
  double rss_max_mib = 0.0;  // after the reference
  double rss_growth_percent = 0.0;
  double frame_cpu_median_first_ms = 0.0;
  double frame_cpu_median_last_ms = 0.0;
  double frame_cpu_drift_percent = 0.0;
  double frame_wall_median_first_ms = 0.0;
  double frame_wall_median_last_ms = 0.0;
  double frame_wall_drift_percent = 0.0;
  bool rss_growth_ok = false;
};

// Throws std::invalid_argument when no sample reaches rss_reference_s (a run too short for the
// check) or the samples are not in increasing time.
SoakFigures ComputeSoakFigures(const std::vector<SoakSample>& samples,
                               const SoakCheckParams& check);

// summary.json's "soak" section (figures) and its "acceptance" map.
nlohmann::json SoakFiguresJson(const SoakFigures& figures);
nlohmann::json SoakAcceptanceJson(const SoakFigures& figures);

}  // namespace aperture::experiments
