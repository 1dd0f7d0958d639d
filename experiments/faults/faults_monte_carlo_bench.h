#pragma once
// `aperture bench faults` as a Monte-Carlo bench (experiments/bench/monte_carlo_bench.h): whole,
// sharded (`--shard K/N`) and merged through one path. Trial k is faults_bench.h's trial k; its
// record is FlyFaultTrial's. Configuration: {"options": FaultsBenchOptionsToJson}. Outputs:
// summary.json (inputs, baseline, faults, failures, acceptance), flights.csv, report.html.
#include <memory>
#include <nlohmann/json.hpp>

#include "experiments/bench/monte_carlo_bench.h"
#include "experiments/faults/faults_bench.h"

namespace aperture::experiments {

inline constexpr const char* kFaultsBenchName = "faults";

nlohmann::json FaultsBenchConfiguration(const FaultsBenchOptions& options);

// std::invalid_argument (or config::UsageError) naming the bad key, option, scenario or --set
// item: the flight is set up once (not flown) before any trial.
std::unique_ptr<MonteCarloBench> MakeFaultsMonteCarloBench(const nlohmann::json& configuration);

}  // namespace aperture::experiments
