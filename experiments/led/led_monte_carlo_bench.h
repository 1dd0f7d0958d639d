#pragma once
// `aperture bench led` as a Monte-Carlo bench (experiments/bench/monte_carlo_bench.h): whole,
// sharded (`--shard K/N`) and merged through one path. A trial is one section of the bench
// (led_bench.h): trial k is the k-th of the sections selected, in LedBenchSectionKeys() order.
// Each section renders and tracks its own sequence from its own seed (the bench seed plus the
// section's offset) and frame indices, so it gives the same figures in any shard; the tracker
// carries its state from frame to frame, so a section is not cut further. Its record is
// RunLedBenchSection's; the timing section is computed by the writer over the sections' stage
// times (wall-clock measurements of each process, not figures). Configuration:
//   {"options": {"seed", "quick", "only"}}
#include <memory>
#include <nlohmann/json.hpp>

#include "experiments/bench/monte_carlo_bench.h"
#include "experiments/led/led_bench.h"

namespace aperture::experiments {

inline constexpr const char* kLedBenchName = "led";

// frames_csv_path is not part of it (the writer puts frames.csv into the output folder).
nlohmann::json LedBenchConfiguration(const LedBenchOptions& options);

// std::invalid_argument naming the bad key or section.
std::unique_ptr<MonteCarloBench> MakeLedMonteCarloBench(const nlohmann::json& configuration);

}  // namespace aperture::experiments
