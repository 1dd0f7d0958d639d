#pragma once
// What every Monte-Carlo bench command shares (`aperture bench gap`, ...): --shard K/N and
// --threads T, and the run through experiments::RunMonteCarloBench, which builds the bench from
// its configuration through the registry of Monte-Carlo benches, so every such command shards
// and merges (`aperture bench merge`) the same way.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "experiments/bench/monte_carlo_bench_registry.h"
#include "output/output_folder.h"

namespace aperture::apps {

struct MonteCarloCommandOptions {
  std::string shard;  // "K/N"; empty = the whole run
  int threads = 0;    // concurrent trials; 0 = all cores
};

// The Monte-Carlo benches of this program: the library's (MonteCarloBenchRegistry::WithBuiltins),
// `bench tags` with ViSP's tag detector besides the built-in ones. `aperture bench NAME` and
// `aperture bench merge` build their benches through it.
experiments::MonteCarloBenchRegistry BenchRegistry();

// Adds --shard (checked: K/N with 1 <= K <= N, else exit 2) and --threads to `command`.
void AddMonteCarloOptions(CLI::App* command, MonteCarloCommandOptions* options);

// Runs the registered bench `name` built from `configuration` into `out` (whole, or the shard)
// with a progress bar, and prints its outcome line. SIGINT/SIGTERM stop it between trials: the
// finished trials' records are written (experiments/bench/monte_carlo_run.h).
void RunMonteCarloCommand(const std::string& name, const nlohmann::json& configuration,
                          const MonteCarloCommandOptions& options, output::OutputFolder& out);

}  // namespace aperture::apps
