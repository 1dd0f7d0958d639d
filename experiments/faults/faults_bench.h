#pragma once
// `aperture bench faults` (issue 18 item 5): a scenario's default mission (`aperture sim
// SCENARIO`: gap, led, ...) flown through experiments::FlyMission with one fault at a time
// (fault_injection.h) at each level of its sweep, every flight counted as success, safe abort or
// crash (flight_outcome.h). Each repeat r draws one condition (its seed: sensor noise and drops;
// for `gap` also the gap's roll 0-45 deg and pitch 0-30 deg, the paper's range) and flies it
// without a fault (the baseline, level 0 of every sweep) and with every fault at every level: the
// flights of a repeat differ only by the fault (paired comparisons).
//
// Trials, repeat-major (an interrupted run is balanced): trial k is repeat k / P, slot k % P of
// P = 1 + faults x levels; slot 0 is the baseline, slot 1 + f * L + l fault f at its l-th level
// above none (L = 4 for the sweep, 2 with `acceptance_levels`: the default and twice it).
//
// Acceptance (issue 18): no crash at any fault's default level, crashes <= 5 % at twice it.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/faults/fault_injection.h"
#include "experiments/faults/flight_outcome.h"
#include "output/html_report.h"

namespace aperture::experiments {

struct FaultsBenchOptions {
  std::string scenario = "gap";  // a built-in scenario; its default mission is flown
  int repeats = 10;              // conditions, each flown at every level of every fault
  std::uint64_t seed = 1;
  double duration_s = 15.0;            // simulated per flight (the mission may end earlier) [s]
  std::vector<std::string> faults;     // names (fault_injection.h); empty = all
  bool acceptance_levels = false;      // only the default level and twice it (plus the baseline)
  std::vector<std::string> set_items;  // scenario keys and mission.* for every flight

  // std::invalid_argument naming the option: repeats < 1, non-positive duration, an unknown or
  // repeated fault.
  void Validate() const;
  std::vector<FaultSpec> SelectedFaults() const;  // in catalogue order
  std::vector<double> LevelsAboveNone(const FaultSpec& fault) const;
  int TrialsPerRepeat() const;
  int Trials() const { return repeats * TrialsPerRepeat(); }
};

nlohmann::json FaultsBenchOptionsToJson(const FaultsBenchOptions& options);
FaultsBenchOptions FaultsBenchOptionsFromJson(const nlohmann::json& json);  // invalid_argument

// What trial k flies.
struct FaultTrialPlan {
  int repeat = 0;
  std::string fault = "none";  // "none" for the baseline
  double level = 0.0;
  std::uint64_t seed = 0;                    // the flight's (scenario, sensors)
  std::uint64_t fault_seed = 0;              // DrawFault's
  std::vector<std::string> condition_items;  // per repeat (gap: roll and pitch)
};
FaultTrialPlan PlanFaultTrial(const FaultsBenchOptions& options, int trial);
// The `aperture sim` command line (without --out) that flies trial k's flight again, with video:
// the same seed, condition, duration, --set items and fault (--fault NAME=LEVEL --fault-seed N).
std::string ReplayCommand(const FaultsBenchOptions& options, const FaultTrialPlan& plan);

// Flies trial k; errors of the flight become a record with outcome "error" (counted as a crash).
// Record: {"repeat", "fault", "level", "seed", "fault_seed", "condition", "replay", "outcome",
// "reason", "mission_passed", "mission_outcome", "sim_outcome", "sim_time_s", "wall_time_s"}.
nlohmann::json FlyFaultTrial(const FaultsBenchOptions& options, int trial);

// summary.json "faults" (per fault and level: trials, success, safe_abort, crash and rates; the
// baseline as level none), "baseline", "acceptance"; writes flights.csv to `flights_csv_path`
// and the report's sections (success / safe abort / crash vs level, one plot per fault).
void WriteFaultsBenchSections(const FaultsBenchOptions& options,
                              const std::vector<nlohmann::json>& records,
                              const std::string& flights_csv_path, nlohmann::json* summary,
                              output::HtmlReport* report);

}  // namespace aperture::experiments
