#pragma once
// `aperture bench tags` as a Monte-Carlo bench (experiments/bench/monte_carlo_bench.h): whole,
// sharded (`--shard K/N`) and merged through one path. A trial is one section of the bench
// (tag_bench.h) of those selected (all by default: trial 0 detection, 1 mapping, 2 missions),
// each drawn from the bench seed alone. Its
// record is RunTagBenchSection's. The detectors are those of the registry the factory is made
// with (the command adds ViSP's); the configuration names them, so shards of one run merge only
// with a build that has the same detectors. Configuration:
//   {"options": {"seed", "quick", "detectors": [names], "sections": [keys, empty = all]}}
// Figures that are measurements of the process that ran them: detection.*.median_ms,
// mapping.map_solve_time_s and missions.timing. mapping.map_tags[].sigma_m (from Ceres' covariance)
// differs between runs in the last bits.
#include <nlohmann/json.hpp>

#include "experiments/bench/monte_carlo_bench_registry.h"
#include "experiments/tags/tag_bench.h"

namespace aperture::experiments {

inline constexpr const char* kTagsBenchName = "tags";

// options.detectors' names are recorded; frames_csv_path is not (the writer puts frames.csv into
// the output folder).
nlohmann::json TagsBenchConfiguration(const TagBenchOptions& options);

// A factory whose benches detect with `detectors`; it throws std::invalid_argument naming the
// bad key, or detectors that differ from the configuration's.
MonteCarloBenchFactory MakeTagsMonteCarloBenchFactory(perception::TagDetectorRegistry detectors);

}  // namespace aperture::experiments
