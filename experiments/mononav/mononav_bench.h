#pragma once
// `aperture bench mononav` (issue 17; seed 003 Tables II and IV, Sec. IV timing): seeded SITL
// flights of the `forest` mission (experiments/missions/forest_flight.h) through random forest
// layouts (one per seed, goal 22 m away), each scored by EvaluateForestFlight on ground truth:
//   table_iv   success with and without the ego-dynamic transform (same layouts)
//   table_ii   replans (segments rejected by their spatial windows, the next best then tried)
//              with the optimal and a random waypoint order (same layouts, with EDT): per flight,
//              per waypoint selection (one per frame not flying straight to the goal) and the
//              share of selections with any
//   success    success / failure counts of every configuration flown, with the flights'
//              recoveries (back-offs along the flown path, look-asides at rest)
//   timing     per-frame thread CPU of perception (depth map) and planning (EDT, selection,
//              spline) over every frame of the EDT flights: median and max [ms]
//   acceptance the checks as booleans (those whose configurations were flown)
// Flights run one after another (deterministic; each flight is a function of its seed). The bench
// runs as a Monte-Carlo bench (mononav_monte_carlo_bench.h: whole or sharded); a trial is one
// layout flown in every configuration.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/missions/mission_registry.h"
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
  // edt and no_edt, Table II edt and random_waypoint, the timing edt; a table row, the timing or an
  // acceptance check whose configurations were not flown is left out. Empty = all three.
  std::vector<std::string> configurations;
  // Overrides of the `forest` scenario and of the mission (`mission.*`), applied to every flight.
  std::vector<std::string> set_items;
  std::string flights_csv_path;  // one row per flight; empty = none

  void Validate() const;    // std::invalid_argument naming the option
  int LayoutCount() const;  // the layouts flown: 1 when quick, else trials
};

// One flight of one configuration ("edt", "no_edt", "random_waypoint") over one layout.
struct MononavFlight {
  std::string configuration;
  std::uint64_t seed = 0;  // the layout's scenario seed
  MissionEvaluation evaluation;
  std::string outcome;  // sim::ToString(SitlResult::Outcome)
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
};

// Layout `layout` (scenario seed first_seed + layout) flown in every chosen configuration (edt
// only when quick, else `configurations`, empty = all), in the order edt, no_edt,
// random_waypoint.
std::vector<MononavFlight> FlyMononavLayout(const MononavBenchOptions& options, int layout);

// From the flights of every layout (layout-major, configurations in order): fills
// (*summary)[section] for the sections above, writes flights_csv_path and adds tables and plots
// to *report.
void WriteMononavSections(const MononavBenchOptions& options,
                          const std::vector<MononavFlight>& flights, nlohmann::json* summary,
                          output::HtmlReport* report);

// A flight as JSON and back, exactly (the trial records of the Monte-Carlo bench).
// std::invalid_argument naming a missing or malformed key.
nlohmann::json MononavFlightToJson(const MononavFlight& flight);
MononavFlight MononavFlightFromJson(const nlohmann::json& json);

}  // namespace aperture::experiments
