#pragma once
// `aperture bench gapflyt` (issue 14; seed 002 Sec. IV, the 85 % over 150 trials analog):
// closed-loop GapFlyt flights (experiments/missions/gapflyt_flight.h: scan, TS²P, label tracking,
// servo, go through) in randomized `gapflyt` scenes, for each servo law, scored by the mission's
// one evaluator (gapflyt_evaluation.h). Trial k of a seed draws (from a generator of (seed, k)
// only): the shape kTs2pShapes[k % 5], the scene seed (textures, polygon corners, sensor noise),
// the wall and background distances, the opening's size and its offset from the start's line of
// sight. Every law flies the same trials. Tight trials (every tight_every-th round of the five
// shapes) stretch the opening's width until its narrowest passage is tight_margin_m wider than
// the vehicle (tight_opening.h: the level footprint's best placement clears the edge by
// tight_margin_m / 2), so a tight star is as tight as a tight ellipse.
//
//   success  (the mission's `passed`) crossed inside the opening, no collision;
//   seed 002 success  the same and the detection the servo started from overlapped the true
//            opening by >= 75 % (Sec. IV-C).
//
//   GapflytTrialRecord flight = RunGapflytTrial(options, DrawGapflytTrial(options, k), "moments");
//   WriteGapflytBenchOutputs(result, out);  // summary.json, trials.csv, report.html
//
// The bench runs as a Monte-Carlo bench (gapflyt_monte_carlo_bench.h: whole or sharded); trials
// run one after another (each a few CPU seconds at the default 320 x 240).
#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "output/output_folder.h"

namespace aperture::experiments {

struct GapflytTrialRanges {
  Eigen::Vector2d foreground_x_m = Eigen::Vector2d(2.2, 3.0);  // around seed 002's 2.6 m
  Eigen::Vector2d background_x_m = Eigen::Vector2d(5.0, 6.5);  // around 5.7 m
  Eigen::Vector2d width_m = Eigen::Vector2d(0.8, 1.2);         // opening bounding box
  Eigen::Vector2d height_m = Eigen::Vector2d(0.6, 1.0);
  double max_offset_m = 0.2;  // opening centre off the start's line of sight, per axis
};

struct GapflytBenchOptions {
  int trials = 50;  // per law
  std::uint64_t seed = 1;
  std::vector<std::string> laws{"moments", "pid"};
  GapflytTrialRanges ranges;
  // Every tight_every-th round of the five shapes is tight (0: none): 5 = one round in five.
  int tight_every = 5;
  double tight_margin_m = 0.05;  // narrowest passage - vehicle width in tight trials [m]
  // Image size of the forward camera (the scenario's 80 deg pinhole): 320 x 240 keeps a flight
  // at a few CPU seconds; the TS²P and tracker radii scale with the width.
  int width = 320;
  int height = 240;
  double duration_s = 14.0;  // per flight; the mission is done after ~8-9 s
  // `mission.*` overrides for every flight (e.g. "mission.go_through_speed_mps=1.5").
  std::vector<std::string> mission_set_items;
  void Validate() const;  // std::invalid_argument naming the option
};

struct GapflytTrialConfig {
  int trial = 0;
  std::string shape;
  std::uint64_t scene_seed = 0;
  double foreground_x_m = 2.6;
  double background_x_m = 5.7;
  Eigen::Vector2d size_m = Eigen::Vector2d(1.0, 0.8);
  Eigen::Vector2d center_m = Eigen::Vector2d(0.0, 1.5);  // (y_W, z_W)
  bool tight = false;
};

struct GapflytTrialRecord {
  GapflytTrialConfig config;
  std::string law;
  bool passed = false;
  bool seed002_success = false;
  nlohmann::json figures;  // the mission's evaluation figures
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
};

struct GapflytBenchResult {
  GapflytBenchOptions options;
  std::vector<GapflytTrialRecord> trials;  // law-major, trial order
};

// Trial `trial` of a bench seeded `seed` (see the header).
GapflytTrialConfig DrawGapflytTrial(const GapflytBenchOptions& options, int trial);

// The `aperture sim gapflyt` command line that flies trial `config` with `law` again (same scene,
// sensor noise and mission overrides; video and plots of one failure).
std::string GapflytTrialSimCommand(const GapflytBenchOptions& options,
                                   const GapflytTrialConfig& config, const std::string& law);

// Flies one trial with one law. Exceptions inside the flight are recorded as its failure.
GapflytTrialRecord RunGapflytTrial(const GapflytBenchOptions& options,
                                   const GapflytTrialConfig& config, const std::string& law);


// Per law: trials, success_rate, seed002_success_rate, tight_success_rate, clearance_m and
// time_to_cross_s (mean / min / max over the crossings), per_shape success rates; "per_trial".
nlohmann::json SummarizeGapflytBench(const GapflytBenchResult& result);

// summary.json (SummarizeGapflytBench), trials.csv (one row per flight), report.html.
void WriteGapflytBenchOutputs(const GapflytBenchResult& result, output::OutputFolder& out);

// The options and the flights as JSON and back, exactly (gapflyt_bench_json.cc): the
// configuration and trial records of the Monte-Carlo bench (gapflyt_monte_carlo_bench.h).
// std::invalid_argument naming a missing or malformed key.
nlohmann::json GapflytBenchOptionsToJson(const GapflytBenchOptions& options);
GapflytBenchOptions GapflytBenchOptionsFromJson(const nlohmann::json& json);
nlohmann::json GapflytTrialRecordToJson(const GapflytTrialRecord& record);
GapflytTrialRecord GapflytTrialRecordFromJson(const nlohmann::json& json);

}  // namespace aperture::experiments
