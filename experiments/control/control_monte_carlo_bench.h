#pragma once
// `aperture bench control` as a Monte-Carlo bench (experiments/bench/monte_carlo_bench.h):
// whole, sharded (`--shard K/N`) and merged through one path. A trial is one section of the
// bench (control_bench_sections.h): trial k is the k-th section selected. Every section flies
// from the bench vehicle and options.seed alone, so it gives the same figures in any shard; its
// record is RecordSection's (experiments/bench/section_record.h) plus "section". summary.json
// "timing.<key>_s" holds each section's wall time (a measurement of the process that ran it).
// Configuration:
//   {"options": {"seed", "quick", "recovery_trials", "only"},
//    "config": the vehicle and control stack, sections control, dynamics, imu, range, vehicle (a
//    partial
//              one is completed with the defaults; the bench records the full effective one)}
#include <memory>
#include <nlohmann/json.hpp>

#include "config/config_tree.h"
#include "experiments/bench/monte_carlo_bench.h"
#include "experiments/control/control_bench_section.h"

namespace aperture::experiments {

inline constexpr const char* kControlBenchName = "control";

// `config`: the configuration tree's JSON (config::ConfigTree::ToJson) with any of the sections
// control, dynamics, imu, range and vehicle; options' vehicle and stack fields are not read
// (`config` is).
nlohmann::json ControlBenchConfiguration(const ControlBenchOptions& options,
                                         const std::vector<std::string>& only,
                                         const nlohmann::json& config);

// Reads the vehicle and control stack (sections control, dynamics, imu, range, vehicle; unknown
// keys rejected) from `tree` into options, then replaces those sections of `tree` by their full
// effective values. std::invalid_argument naming the value's source (a file line, a --set item)
// and key. The command calls it on its --config/--set tree so that mistakes are named there; the
// bench calls it again on the configuration it is built from.
void ReadControlBenchVehicle(config::ConfigTree* tree, ControlBenchOptions* options);

// std::invalid_argument naming the bad key, section or parameter.
std::unique_ptr<MonteCarloBench> MakeControlMonteCarloBench(const nlohmann::json& configuration);

}  // namespace aperture::experiments
