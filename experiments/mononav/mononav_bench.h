#pragma once
// `aperture bench mononav` (issue 17; seed 003 Tables II and IV, Sec. IV timing): seeded SITL
// flights of the `forest` mission (experiments/missions/forest_flight.h) through random forest
// layouts (one per seed, goal 22 m away), each scored by EvaluateForestFlight on ground truth:
//   table_iv   success with and without the ego-dynamic transform (same layouts)
//   table_ii   replans (segments rejected by their spatial windows) with the optimal and a random
//              waypoint order (same layouts, with EDT)
//   timing     per-frame thread CPU of perception (depth map) and planning (EDT, selection,
//              spline) over every frame of the EDT flights: median and max [ms]
//   acceptance the checks as booleans
// Flights run one after another (deterministic; each flight is a function of its seed).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "output/html_report.h"

namespace aperture::experiments {

struct MononavBenchOptions {
  int trials = 40;               // forest layouts (seeds first_seed ..)
  std::uint64_t first_seed = 1;  // scenario seed of the first layout (also its sensor noise)
  double duration_s = 60.0;      // per flight, unless the mission reaches its goal earlier [s]
  // One flight, the EDT configuration only, on a short course (goal 4 m away, one trunk 2 m
  // ahead on the line): the same code paths for tests and quick looks.
  bool quick = false;
  // Which configurations to fly on every layout (edt | no_edt | random_waypoint); Table IV needs
  // edt and no_edt, Table II edt and random_waypoint. Empty = all three.
  std::vector<std::string> configurations;
  // Overrides of the `forest` scenario and of the mission (`mission.*`), applied to every flight.
  std::vector<std::string> set_items;
  std::string flights_csv_path;  // one row per flight; empty = none

  void Validate() const;  // std::invalid_argument naming the option
};

// Fills (*summary)[section] for the sections above and adds tables and plots to *report.
void RunMononavBench(const MononavBenchOptions& options, nlohmann::json* summary,
                     output::HtmlReport* report);

}  // namespace aperture::experiments
