#pragma once
// Monte-Carlo benches by name ("gap"). `aperture bench NAME` builds its bench through here and
// `aperture bench merge` rebuilds it from a shard's recorded configuration, so a bench that runs
// through the registry is shardable and mergeable by construction (monte_carlo_run.h runs only
// registered benches).
//
//   MonteCarloBenchRegistry benches = MonteCarloBenchRegistry::WithBuiltins();
//   std::unique_ptr<MonteCarloBench> bench = benches.Create("gap", configuration);
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/bench/monte_carlo_bench.h"
#include "perception/tags/tag_detector_registry.h"

namespace aperture::experiments {

// Builds a bench from its configuration (MonteCarloBench::configuration() of an earlier build is
// accepted too); std::invalid_argument naming the bad key or value.
using MonteCarloBenchFactory =
    std::function<std::unique_ptr<MonteCarloBench>(const nlohmann::json& configuration)>;

class MonteCarloBenchRegistry {
 public:
  // The benches of this library: "control" (experiments/control/control_monte_carlo_bench.h),
  // "faults" (experiments/faults/faults_monte_carlo_bench.h),
  // "gap" (experiments/gap/gap_monte_carlo_bench.h), "gapflyt"
  // (experiments/gapflyt/gapflyt_monte_carlo_bench.h), "led"
  // (experiments/led/led_monte_carlo_bench.h), "mononav"
  // (experiments/mononav/mononav_monte_carlo_bench.h), "tags" with `tag_detectors`
  // (experiments/tags/tags_monte_carlo_bench.h), "ts2p"
  // (experiments/ts2p/ts2p_monte_carlo_bench.h); and the benches declared unsharded: "soak"
  // (apps/bench_soak_command.cc).
  static MonteCarloBenchRegistry WithBuiltins(const perception::TagDetectorRegistry& tag_detectors =
                                                  perception::TagDetectorRegistry::WithBuiltins());

  // std::invalid_argument for an empty or repeated name (also one declared unsharded) or an
  // empty factory.
  void Register(const std::string& name, MonteCarloBenchFactory factory);
  std::vector<std::string> Names() const;  // sorted
  bool Contains(const std::string& name) const { return factories_.count(name) > 0; }
  // std::invalid_argument for an unknown name (listing the known ones) or a bad configuration.
  std::unique_ptr<MonteCarloBench> Create(const std::string& name,
                                          const nlohmann::json& configuration) const;

  // A bench of `aperture bench` that takes no --shard, and why (a fixed, deterministic
  // measurement that is no set of trials, or not converted yet). Every `aperture bench`
  // subcommand but `merge` is either registered or declared here, which
  // tests/apps/bench_shard_command_test.cc checks: a new bench that is neither fails it.
  // std::invalid_argument for an empty name or reason, or a name registered or declared before.
  void DeclareUnsharded(const std::string& name, const std::string& reason);
  const std::map<std::string, std::string>& unsharded() const { return unsharded_; }

 private:
  std::map<std::string, MonteCarloBenchFactory> factories_;
  std::map<std::string, std::string> unsharded_;  // name -> reason
};

}  // namespace aperture::experiments
