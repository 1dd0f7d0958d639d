#include "experiments/bench/monte_carlo_bench_registry.h"

#include <stdexcept>

#include "experiments/control/control_monte_carlo_bench.h"
#include "experiments/faults/faults_monte_carlo_bench.h"
#include "experiments/gap/gap_monte_carlo_bench.h"
#include "experiments/gapflyt/gapflyt_monte_carlo_bench.h"
#include "experiments/led/led_monte_carlo_bench.h"
#include "experiments/mononav/mononav_monte_carlo_bench.h"
#include "experiments/tags/delivery_monte_carlo_bench.h"
#include "experiments/tags/tags_monte_carlo_bench.h"
#include "experiments/ts2p/ts2p_monte_carlo_bench.h"

namespace aperture::experiments {

MonteCarloBenchRegistry MonteCarloBenchRegistry::WithBuiltins(
    const perception::TagDetectorRegistry& tag_detectors) {
  MonteCarloBenchRegistry registry;
  registry.Register(kControlBenchName, &MakeControlMonteCarloBench);
  registry.Register(kDeliveryBenchName, &MakeDeliveryMonteCarloBench);
  registry.Register(kFaultsBenchName, &MakeFaultsMonteCarloBench);
  registry.Register(kGapBenchName, &MakeGapMonteCarloBench);
  registry.Register(kGapflytBenchName, &MakeGapflytMonteCarloBench);
  registry.Register(kLedBenchName, &MakeLedMonteCarloBench);
  registry.Register(kMononavBenchName, &MakeMononavMonteCarloBench);
  registry.Register(kTagsBenchName, MakeTagsMonteCarloBenchFactory(tag_detectors));
  registry.Register(kTs2pBenchName, &MakeTs2pMonteCarloBench);
  registry.DeclareUnsharded("soak",
                            "one flight for a simulated hour: its figures are one process's memory "
                            "and per-frame time over time, which shards cannot split");
  return registry;
}

void MonteCarloBenchRegistry::Register(const std::string& name, MonteCarloBenchFactory factory) {
  if (name.empty() || !factory) {
    throw std::invalid_argument("MonteCarloBenchRegistry: a bench needs a name and a factory");
  }
  if (unsharded_.count(name) > 0 || !factories_.emplace(name, std::move(factory)).second) {
    throw std::invalid_argument("MonteCarloBenchRegistry: bench '" + name +
                                "' is registered or declared twice");
  }
}

void MonteCarloBenchRegistry::DeclareUnsharded(const std::string& name, const std::string& reason) {
  if (name.empty() || reason.empty()) {
    throw std::invalid_argument(
        "MonteCarloBenchRegistry: an unsharded bench needs a name and the reason it is");
  }
  if (factories_.count(name) > 0 || !unsharded_.emplace(name, reason).second) {
    throw std::invalid_argument("MonteCarloBenchRegistry: bench '" + name +
                                "' is registered or declared twice");
  }
}

std::vector<std::string> MonteCarloBenchRegistry::Names() const {
  std::vector<std::string> names;
  for (const auto& entry : factories_) names.push_back(entry.first);
  return names;
}

std::unique_ptr<MonteCarloBench> MonteCarloBenchRegistry::Create(
    const std::string& name, const nlohmann::json& configuration) const {
  const auto it = factories_.find(name);
  if (it == factories_.end()) {
    std::string known;
    for (const std::string& n : Names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown Monte-Carlo bench '" + name + "' (known: " + known + ")");
  }
  return it->second(configuration);
}

}  // namespace aperture::experiments
