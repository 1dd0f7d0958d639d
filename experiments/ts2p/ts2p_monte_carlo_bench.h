#pragma once
// `aperture bench ts2p` as a Monte-Carlo bench (experiments/bench/monte_carlo_bench.h): whole,
// sharded (`--shard K/N`) and merged through one path. A trial is a unit of ts2p_bench_trials.h
// (one rendered scan: a detection trial with its sweeps and example image, a depth-sweep scan or
// a tracking approach), its record Ts2pBenchTrials::Run's. Configuration:
//   {"quick": bool, "options": Ts2pBenchOptionsToJson(options) (methods filled in),
//    "config": the configuration tree's JSON with sections ts2p (the detector) and gap_tracker}
// Figures that are measurements of the process that ran them (as in any two whole runs): every
// series' time_ms, acceptance.cpu_ms / wall_ms and acceptance.met (its CPU budget), tracking's
// *_ms, the *_ms columns of trials.csv, and best_method only where two methods tie on DR (the
// faster one wins).
#include <memory>
#include <nlohmann/json.hpp>

#include "config/config_tree.h"
#include "experiments/bench/monte_carlo_bench.h"
#include "experiments/ts2p/ts2p_bench.h"

namespace aperture::experiments {

inline constexpr const char* kTs2pBenchName = "ts2p";

// `config`: the configuration tree's JSON (config::ConfigTree::ToJson); options.detector and
// options.tracker are not recorded (`config` is). `quick` is recorded in summary.json (the caller
// sets the quick run's options).
nlohmann::json Ts2pBenchConfiguration(const Ts2pBenchOptions& options, bool quick,
                                      const nlohmann::json& config);

// Reads the detector (section `ts2p`) and the tracker (`gap_tracker`) from `tree` into options;
// other sections are rejected. std::invalid_argument naming the value's source (a file line, a
// --set item) and key. The command calls it on its --config/--set tree so that mistakes are named
// there; the bench calls it again on the configuration it is built from.
void ReadTs2pBenchParams(const config::ConfigTree& tree, Ts2pBenchOptions* options);

// std::invalid_argument naming the bad key, option or parameter.
std::unique_ptr<MonteCarloBench> MakeTs2pMonteCarloBench(const nlohmann::json& configuration);

}  // namespace aperture::experiments
