#pragma once
// `aperture bench mononav` as a Monte-Carlo bench (experiments/bench/monte_carlo_bench.h): whole,
// sharded (`--shard K/N`) and merged through one path. Trial k is the forest layout of scenario
// seed first_seed + k flown in every configuration; its record is
// {"trial": k, "flights": [MononavFlightToJson per configuration]}. Configuration:
//   {"options": {"trials", "first_seed", "duration_s", "quick", "configurations", "set_items"}}
// The outputs are those of mononav_bench.h plus summary "inputs", flights.csv and report.html.
#include <memory>
#include <nlohmann/json.hpp>

#include "experiments/bench/monte_carlo_bench.h"
#include "experiments/mononav/mononav_bench.h"

namespace aperture::experiments {

inline constexpr const char* kMononavBenchName = "mononav";

// flights_csv_path is not part of it (the writer puts flights.csv into the output folder).
nlohmann::json MononavBenchConfiguration(const MononavBenchOptions& options);

// std::invalid_argument naming the bad key or option.
std::unique_ptr<MonteCarloBench> MakeMononavMonteCarloBench(const nlohmann::json& configuration);

}  // namespace aperture::experiments
