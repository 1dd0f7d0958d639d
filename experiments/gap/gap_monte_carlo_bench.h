#pragma once
// `aperture bench gap` as a Monte-Carlo bench (experiments/bench/monte_carlo_bench.h): whole,
// sharded (`--shard K/N`) and merged through one path. Its configuration is
//   {"autopilot": "mission" | "ground_truth", "options": GapBenchOptionsToJson(options),
//    "config": the effective scenario and mission configuration (filled in by the bench)}
// and a trial record is GapTrialRecordToJson (gap_trial_record_json.h). Trials are drawn from
// (seed, global index) only (DrawGapTrial), so a trial flies the same in any shard.
//
//   nlohmann::json configuration = GapBenchConfiguration(options, "mission");
//   std::unique_ptr<MonteCarloBench> bench = MakeGapMonteCarloBench(configuration);
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "experiments/bench/monte_carlo_bench.h"
#include "experiments/gap/gap_bench.h"

namespace aperture::experiments {

inline constexpr const char* kGapBenchName = "gap";

// `autopilot`: "mission" (the vision gap mission on rendered frames) or "ground_truth" (the same
// traverse on ground truth; no camera is rendered).
nlohmann::json GapBenchConfiguration(const GapBenchOptions& options, const std::string& autopilot);

// std::invalid_argument naming the bad key, option or scenario override.
std::unique_ptr<MonteCarloBench> MakeGapMonteCarloBench(const nlohmann::json& configuration);

}  // namespace aperture::experiments
