#pragma once
// The units of work of `aperture bench ts2p` (ts2p_bench.h), the trials of its Monte-Carlo bench
// (ts2p_monte_carlo_bench.h): every rendered scan is one unit, a pure function of (options, unit
// index), and its record holds every score, tracking series and example image the writer reads,
// so summary.json, trials.csv and report.html come out the same from one process or from merged
// shards. A unit is one of
//   detection  trial t of Table II: every method on one N = 4 scan; for t < sweep_trials also the
//              N and image-size sweeps (Figs. 13, 12) on that scan, and for the first trial of
//              each shape the Fig. 10 overlay (an example image);
//   depth      scan i at foreground depth d of the Z_F sweep (Fig. 9);
//   tracking   the approach after a detection on trial t's scan (Table III).
// The unit indices interleave four sequences evenly (detection trials with sweeps, the other
// detection trials, depth scans, tracking approaches), each in its own order, so that a block of
// indices (a shard) gets its share of every kind: a sweep trial or an approach costs several
// plain detection trials, and a block of the first trials alone would hold all of them.
//
//   Ts2pBenchTrials trials(options);                 // methods filled in
//   for (int k = 0; k < Ts2pBenchTrialCount(options); ++k) records.push_back(trials.Run(k));
//   Ts2pBenchResult result = Ts2pBenchResultFromRecords(options, records);
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "experiments/ts2p/ts2p_bench.h"

namespace aperture::experiments {

// trials + foreground_depths_m.size() * depth_trials + tracking_trials.
int Ts2pBenchTrialCount(const Ts2pBenchOptions& options);

// Renders and scores units one at a time. OpenCV runs on one thread while it lives (detection
// CPU times are "on one core"); the renderer's rows run in parallel in the caller's task arena.
class Ts2pBenchTrials {
 public:
  // `options` validated (std::invalid_argument), methods as given (none: no Table II rows).
  explicit Ts2pBenchTrials(const Ts2pBenchOptions& options);
  ~Ts2pBenchTrials();

  // Unit `unit` (0 <= unit < Ts2pBenchTrialCount) as a JSON record:
  //   {"kind": "detection" | "depth" | "tracking", "index": the trial or scan of its kind,
  //    "outcomes": [{"group": "methods" | "stacks" | "sizes" | "depths", "series", "x", "trial",
  //                  "shape", "valid", "overlap", "false_negative", "false_positive",
  //                  "timing": {Ts2pTiming's fields}}],
  //    "examples": [{"shape", "png": the overlay as PNG bytes (binary)}],
  //    "tracking": {"trial", "drift_px", "filtered_drift_px", "propagation_ms", "klt_ms",
  //                 "resets"} (tracking units only)}
  // std::out_of_range for an index outside the run.
  nlohmann::json Run(int unit);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The result of the units' records, all of them in index order (any other order or a missing
// record: std::invalid_argument): series in the order a sequential run meets them.
Ts2pBenchResult Ts2pBenchResultFromRecords(const Ts2pBenchOptions& options,
                                           const std::vector<nlohmann::json>& records);

}  // namespace aperture::experiments
