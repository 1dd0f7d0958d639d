#include "experiments/ts2p/ts2p_monte_carlo_bench.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/ts2p/ts2p_bench_trials.h"
#include "perception/flow/dense_flow.h"

namespace aperture::experiments {
namespace {

class Ts2pMonteCarloBench : public MonteCarloBench {
 public:
  explicit Ts2pMonteCarloBench(const nlohmann::json& configuration) {
    nlohmann::json config;
    try {
      quick_ = configuration.at("quick").get<bool>();
      options_ = Ts2pBenchOptionsFromJson(configuration.at("options"));
      config = configuration.at("config");
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(std::string("bench ts2p configuration: ") + e.what());
    }
    // JSON is YAML: the tree reads the recorded configuration as it reads a --config file.
    config::ConfigTree tree;
    if (!config.is_null()) tree.MergeYaml(config.dump(), "bench ts2p configuration");
    ReadTs2pBenchParams(tree, &options_);
    if (options_.methods.empty()) options_.methods = perception::DenseFlowMethodNames();
    options_.Validate();
    configuration_ = Ts2pBenchConfiguration(options_, quick_, nlohmann::json::parse(tree.ToJson()));
  }

  const nlohmann::json& configuration() const override { return configuration_; }

  TrialRange run() const override { return {0, Ts2pBenchTrialCount(options_)}; }

  // One unit after another (detection CPU times on one core); `threads` bounds the renderer.
  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    Ts2pBenchTrials units(options_);
    return RunTrialsInOrder(trials, threads, on_trial_done, [&](int k) { return units.Run(k); });
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    out.summary()["config"] = configuration_["config"];
    out.summary()["quick"] = quick_;
    WriteTs2pBenchOutputs(Ts2pBenchResultFromRecords(options_, records), out);
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    if (!summary.contains("acceptance")) return "aperture bench ts2p: no method scored";
    const nlohmann::json& a = summary["acceptance"];
    return "aperture bench ts2p: best " + summary["best_method"].get<std::string>() + " DR " +
           a["dr"].dump() + " AFN " + a["afn"].dump() + " AFP " + a["afp"].dump() + " at " +
           a["cpu_ms"].dump() + " ms CPU over " + std::to_string(options_.trials) + " trials";
  }

 private:
  bool quick_ = false;
  Ts2pBenchOptions options_;
  nlohmann::json configuration_;
};

}  // namespace

nlohmann::json Ts2pBenchConfiguration(const Ts2pBenchOptions& options, bool quick,
                                      const nlohmann::json& config) {
  return {{"quick", quick}, {"options", Ts2pBenchOptionsToJson(options)}, {"config", config}};
}

void ReadTs2pBenchParams(const config::ConfigTree& tree, Ts2pBenchOptions* options) {
  config::ParamReader root = tree.Reader();
  root.ReadSection("ts2p", &options->detector);
  root.ReadSection("gap_tracker", &options->tracker);
  root.RejectUnknownKeys();
}

std::unique_ptr<MonteCarloBench> MakeTs2pMonteCarloBench(const nlohmann::json& configuration) {
  return std::make_unique<Ts2pMonteCarloBench>(configuration);
}

}  // namespace aperture::experiments
