#pragma once
// `aperture bench ts2p` (issue 13; seed 002 Sec. IV-B analogs): TS²P detection over rendered
// trials of the five opening shapes with random textures, depths, sizes, offsets and scan
// directions (ts2p_scan.h), scored against the renderer's id masks (opening_score.h):
//   Table II   DR, AFN, AFP and run time per stage for each flow method (N = 4, 576 x 384);
//   Fig. 13    DR/AFN/AFP for N = 2, 4, 8 (the sweep method);
//   Fig. 12    DR/AFN/AFP for image sizes 576x384 -> 48x32 (images area-resampled, G nearest);
//   Fig. 9     DR/AFN/AFP against 0Z_F at 0Z_B = 5.7 m;
//   Table III  label tracking over an approach after the detection: time per frame (KLT,
//              propagation) and the drift of x_s against the safe point of the true opening.
// Each trial is a pure function of (seed, trial index); detection timings are single-threaded
// (cv::setNumThreads(1) while trials run: "on one core"). The bench runs as a Monte-Carlo bench
// (ts2p_monte_carlo_bench.h), whole or in shards: every rendered scan is one unit of work whose
// record holds its scores (ts2p_bench_trials.h), and this writer builds the outputs from them.
//
//   Ts2pBenchResult result = Ts2pBenchResultFromRecords(options, records);
//   WriteTs2pBenchOutputs(result, out);  // summary.json, trials.csv, report.html
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/ts2p/ts2p_scan.h"
#include "output/output_folder.h"
#include "perception/ts2p/label_tracker.h"
#include "perception/ts2p/opening_score.h"
#include "perception/ts2p/ts2p_detector.h"

namespace aperture::experiments {

struct Ts2pBenchOptions {
  int trials = 150;  // Table II: "averaged over 150 trials"
  std::uint64_t seed = 1;
  // Empty: every DenseFlowMethodNames() entry (filled in by the Monte-Carlo bench).
  std::vector<std::string> methods;
  // Sections `ts2p` and `gap_tracker` of the configuration (ReadTs2pBenchParams); not part of
  // Ts2pBenchOptionsToJson.
  perception::Ts2pParams detector;  // flow.method is replaced per method
  Ts2pTrialRanges ranges;
  // The sweeps and the tracking use detector.flow.method on the first trials.
  int sweep_trials = 50;
  std::vector<int> stacks{2, 4, 8};
  std::vector<int> widths{576, 288, 144, 72, 48};                    // height = 2/3 width (Fig. 12)
  std::vector<double> foreground_depths_m{1.5, 2.0, 2.6, 3.2, 4.0};  // Fig. 9 at Z_B 5.7 m
  int depth_trials = 10;                                             // per depth
  int tracking_trials = 5;
  int tracking_frames = 24;         // 0.8 s at 30 Hz
  double tracking_speed_mps = 1.0;  // towards the wall
  perception::LabelTrackerParams tracker;

  void Validate() const;  // std::invalid_argument naming the option
};

// Scores of one configuration (method, N, size or depth) over its trials.
struct Ts2pTrialOutcome {
  int trial = 0;
  std::string shape;
  bool valid = false;
  perception::OpeningScore score;
  perception::Ts2pTiming timing;
};
struct Ts2pSeries {
  std::string name;  // method name, "N=4", "576x384", "Z_F=2.6"
  double x = 0.0;    // the swept value (N, width, Z_F); 0 for methods
  std::vector<Ts2pTrialOutcome> outcomes;
  // Seed 002 Sec. IV-B: DR over all trials, AFN/AFP over the successful ones (NaN if none).
  double DetectionRate() const;
  double AverageFalseNegative() const;
  double AverageFalsePositive() const;
  double MeanTotalMs() const;  // wall-clock
  double MeanCpuMs() const;    // CPU time on the detecting thread
};

struct Ts2pTrackingRun {
  int trial = 0;
  std::vector<double> drift_px;           // |e_k - e_0|, e = x_s (measured) - x_s(G)
  std::vector<double> filtered_drift_px;  // the same for the Kalman-filtered x_s
  std::vector<double> propagation_ms, klt_ms;
  int resets = 0;
};

struct Ts2pBenchResult {
  Ts2pBenchOptions options;
  std::vector<Ts2pSeries> methods, stacks, sizes, depths;
  std::vector<Ts2pTrackingRun> tracking;
  // Overlays of the first trial of each shape (sweep method, N = 4): G and O coloured as
  // seed 002 Fig. 10 (green G ∩ O, yellow missed, red false positive).
  std::vector<std::pair<std::string, cv::Mat>> examples;
};

// The options but `detector` and `tracker` as JSON and back (the Monte-Carlo bench's
// configuration); FromJson: std::invalid_argument naming the missing or mistyped key.
nlohmann::json Ts2pBenchOptionsToJson(const Ts2pBenchOptions& options);
Ts2pBenchOptions Ts2pBenchOptionsFromJson(const nlohmann::json& json);

nlohmann::json SummarizeTs2pBench(const Ts2pBenchResult& result);

// summary.json (SummarizeTs2pBench), trials.csv (one row per trial and method) and report.html.
void WriteTs2pBenchOutputs(const Ts2pBenchResult& result, output::OutputFolder& out);

}  // namespace aperture::experiments
