#pragma once
// Runs a registered Monte-Carlo bench (monte_carlo_bench.h) whole or as one shard, and merges
// shards into the whole run's outputs.
//
//   aperture bench gap --trials 40 --out O                     RunMonteCarloBench, no shard
//   aperture bench gap --trials 40 --shard 2/4 --out S2        RunMonteCarloBench, shard 2/4
//   aperture bench merge --out O S1 S2 S3 S4                   MergeMonteCarloShards
//
// A whole run writes the bench's outputs (MonteCarloBench::WriteOutputs) plus summary "cost":
// threads, cpu_time_s (process CPU of the trial loop, every thread) and cpu_s_per_trial, and
// "code_version". A shard writes summary.json as its manifest (bench, code_version,
// configuration, run, shard with its trial block, cost, host) and its trial records to
// trials.cbor (kShardRecordsFile); no figures, since a part of a run is not a result.
// A run that SIGINT/SIGTERM cut short (output/interruption.h: no further trial starts) writes what
// a shard writes, the records of the trials it finished in trials.cbor and the manifest, with
// "trials_completed"; no figures (summary.json "status": "interrupted").
// A merge checks the shards (each finished; one bench, one code version equal to the merging
// build's, one configuration, blocks that tile the run without gap or overlap), then writes the
// outputs with the bench's own writer from the records in index order: the same summary.json
// figures, per-trial files and report as the whole run, trial by trial bit-identical (wall and
// CPU times aside, which are measurements of each process).
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/bench/monte_carlo_bench_registry.h"
#include "experiments/bench/shard_spec.h"
#include "output/output_folder.h"

namespace aperture::experiments {

inline constexpr const char* kShardRecordsFile = "trials.cbor";

struct MonteCarloRunOptions {
  std::optional<ShardSpec> shard;  // nullopt: the whole run
  int threads = 0;                 // concurrent trials; 0 = all cores this process may use
  std::string code_version;        // recorded; shards merge only with the same one
};

// Shard folders that cannot be merged (bad data: a shard that failed, of another bench, code
// version or configuration, blocks that overlap or leave trials out). The message names the
// folder(s) and what to do.
class ShardMergeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Builds bench `name` from `configuration` through `benches` and runs it into `out` (see the
// header comment). `progress(done, total)` after every trial. std::invalid_argument for an
// unknown bench, a bad configuration or a shard count above the trial count. Returns one line
// for the terminal: the bench's outcome (MonteCarloBench::DescribeOutcome) or the shard's block.
std::string RunMonteCarloBench(const MonteCarloBenchRegistry& benches, const std::string& name,
                               const nlohmann::json& configuration,
                               const MonteCarloRunOptions& options, output::OutputFolder& out,
                               const std::function<void(int, int)>& progress = {});

// What running `trials` trials in `body(used_threads)` costs, for summary.json "cost" of every
// bench: {threads: used_threads (`threads`, or 0 = what oneTBB may use in this process, i.e.
// its CPU affinity), trials, cpu_time_s (process CPU during `body`, every thread),
// cpu_s_per_trial, wall_time_s}. RunMonteCarloBench records it for its trial loop; a bench that
// runs otherwise measures its run with it.
nlohmann::json MeasureTrialCost(int trials, int threads, const std::function<void(int)>& body);

// Merges the shard folders `shard_dirs` (any order) into `out`; the merging build's
// `code_version` must equal the shards'. ShardMergeError when they do not merge (see above).
// Returns the bench's one-line outcome (MonteCarloBench::DescribeOutcome).
std::string MergeMonteCarloShards(const MonteCarloBenchRegistry& benches,
                                  const std::vector<std::string>& shard_dirs,
                                  const std::string& code_version, output::OutputFolder& out);

}  // namespace aperture::experiments
