#pragma once
// `aperture bench gapflyt` as a Monte-Carlo bench (experiments/bench/monte_carlo_bench.h): whole,
// sharded (`--shard K/N`) and merged through one path. Trial k is the draw of (seed, k)
// (DrawGapflytTrial) flown once per servo law; its record holds those flights
// ({"trial": k, "flights": [GapflytTrialRecordToJson per law]}). Configuration:
//   {"quick": bool, "options": GapflytBenchOptionsToJson(options)}
#include <memory>
#include <nlohmann/json.hpp>

#include "experiments/bench/monte_carlo_bench.h"
#include "experiments/gapflyt/gapflyt_bench.h"

namespace aperture::experiments {

inline constexpr const char* kGapflytBenchName = "gapflyt";

// `quick`: recorded in summary.json (the caller sets options.trials = 1, the ellipse).
nlohmann::json GapflytBenchConfiguration(const GapflytBenchOptions& options, bool quick);

// std::invalid_argument naming the bad key or option.
std::unique_ptr<MonteCarloBench> MakeGapflytMonteCarloBench(const nlohmann::json& configuration);

}  // namespace aperture::experiments
