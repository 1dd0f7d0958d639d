#pragma once
// The interface every Monte-Carlo bench of `aperture bench` implements, so that any of them runs
// whole, in shards (`--shard K/N`) and merges (`aperture bench merge`) through one path
// (monte_carlo_run.h). A bench is built from its configuration (JSON, through
// MonteCarloBenchRegistry) and flies trials that are pure functions of (configuration, global
// trial index). Trial records are JSON documents that hold every field the bench's writer reads;
// shards store them as CBOR, which keeps doubles (NaN included) bit for bit, so the writer sees
// the same records whether the trials ran in one process or in many.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/bench/shard_spec.h"
#include "output/output_folder.h"

namespace aperture::experiments {

class MonteCarloBench {
 public:
  virtual ~MonteCarloBench() = default;

  // Everything the trials' results depend on besides their indices: the bench's options, the
  // whole run's trials (`run()`), and the effective scenario and mission configuration. Shards
  // merge only when their configurations are equal. The thread count is not part of it (results
  // do not depend on it).
  virtual const nlohmann::json& configuration() const = 0;

  // The whole (unsharded) run's trial indices.
  virtual TrialRange run() const = 0;

  // Flies trials `trials` (a part of run()), up to `threads` at a time (0 = all cores), and
  // returns one record per trial in index order. `on_trial_done(done)` is called (serialized)
  // after each trial. Failed trials are records too (their failure reason), never exceptions.
  // Once SIGINT/SIGTERM asked to stop (output::InterruptionRequested()) it starts no further
  // trial and returns the records of the trials it finished (fewer than `trials`).
  virtual std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const = 0;

  // summary.json figures, per-trial files and report.html from the records of every trial of
  // run(), in index order: the same writer for a whole run and a merge of shards.
  virtual void WriteOutputs(const std::vector<nlohmann::json>& records,
                            output::OutputFolder& out) const = 0;

  // One line for the terminal from the written summary, e.g. "38/40 successful".
  virtual std::string DescribeOutcome(const nlohmann::json& summary) const = 0;
};

// RunTrials for a bench whose trials run one after another (each trial may render or fly in
// parallel inside): `record_of(k)` (a JSON object) for every k of `trials` inside a task arena of
// `threads` (0 = all cores), each record with "trial": k added; `on_trial_done` after each. It
// stops before the next trial once output::InterruptionRequested().
std::vector<nlohmann::json> RunTrialsInOrder(const TrialRange& trials, int threads,
                                             const std::function<void(int)>& on_trial_done,
                                             const std::function<nlohmann::json(int)>& record_of);

// RunTrials for a bench whose trials are independent flights: the same contract as
// RunTrialsInOrder, but up to `threads` trials at a time (oneTBB parallel_for; `record_of` must
// be safe to call concurrently). Records come back in index order; after an interruption, those
// of the trials that finished.
std::vector<nlohmann::json> RunTrialsInParallel(
    const TrialRange& trials, int threads, const std::function<void(int)>& on_trial_done,
    const std::function<nlohmann::json(int)>& record_of);

}  // namespace aperture::experiments
