#pragma once
// `aperture bench delivery` as a Monte-Carlo bench (experiments/bench/monte_carlo_bench.h): whole,
// sharded (`--shard K/N`) and merged through one path. Trial k is the `tags` field of scenario
// seed first_seed + k flown in every configuration (delivery_bench.h); its record is
// {"trial": k, "flights": [DeliveryFlightToJson per configuration]}. Configuration:
//   {"options": {"trials", "first_seed", "mission", "configurations", "set_items"}}
#include <memory>
#include <nlohmann/json.hpp>

#include "experiments/bench/monte_carlo_bench.h"
#include "experiments/tags/delivery_bench.h"

namespace aperture::experiments {

inline constexpr const char* kDeliveryBenchName = "delivery";

// flights_csv_path is not part of it (the writer puts flights.csv into the output folder).
nlohmann::json DeliveryBenchConfiguration(const DeliveryBenchOptions& options);

// std::invalid_argument naming the bad key or option.
std::unique_ptr<MonteCarloBench> MakeDeliveryMonteCarloBench(const nlohmann::json& configuration);

}  // namespace aperture::experiments
