#include "experiments/gapflyt/gapflyt_monte_carlo_bench.h"

#include <stdexcept>

namespace aperture::experiments {
namespace {

class GapflytMonteCarloBench : public MonteCarloBench {
 public:
  explicit GapflytMonteCarloBench(const nlohmann::json& configuration) {
    if (!configuration.is_object() || !configuration.contains("options") ||
        !configuration.contains("quick")) {
      throw std::invalid_argument(
          "bench gapflyt configuration: expected an object with \"quick\" and \"options\"");
    }
    quick_ = configuration["quick"].get<bool>();
    options_ = GapflytBenchOptionsFromJson(configuration["options"]);
    options_.Validate();
    configuration_ = GapflytBenchConfiguration(options_, quick_);
  }

  const nlohmann::json& configuration() const override { return configuration_; }

  TrialRange run() const override { return {0, options_.trials}; }

  // One trial after another, every law on the same trial; `threads` bounds the renderer's
  // parallelism.
  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    return RunTrialsInOrder(trials, threads, on_trial_done, [&](int k) {
      const GapflytTrialConfig config = DrawGapflytTrial(options_, k);
      nlohmann::json flights = nlohmann::json::array();
      for (const std::string& law : options_.laws) {
        flights.push_back(GapflytTrialRecordToJson(RunGapflytTrial(options_, config, law)));
      }
      return nlohmann::json{{"flights", flights}};
    });
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    GapflytBenchResult result;
    result.options = options_;
    for (const std::string& law : options_.laws) {  // law-major, then trial order
      for (const nlohmann::json& record : records) {
        for (const nlohmann::json& flight : record.at("flights")) {
          if (flight.at("law") == law) result.trials.push_back(GapflytTrialRecordFromJson(flight));
        }
      }
    }
    out.summary()["quick"] = quick_;
    WriteGapflytBenchOutputs(result, out);
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    std::string lines;
    for (const auto& [law, l] : summary["laws"].items()) {
      lines += (lines.empty() ? "" : "\n") + std::string("aperture bench gapflyt: ") + law +
               " passed " + std::to_string(l["passed"].get<int>()) + "/" +
               std::to_string(l["trials"].get<int>()) + " (seed 002 success " +
               l["seed002_success_rate"].dump() + ")";
    }
    return lines;
  }

 private:
  bool quick_ = false;
  GapflytBenchOptions options_;
  nlohmann::json configuration_;
};

}  // namespace

nlohmann::json GapflytBenchConfiguration(const GapflytBenchOptions& options, bool quick) {
  return {{"quick", quick}, {"options", GapflytBenchOptionsToJson(options)}};
}

std::unique_ptr<MonteCarloBench> MakeGapflytMonteCarloBench(const nlohmann::json& configuration) {
  return std::make_unique<GapflytMonteCarloBench>(configuration);
}

}  // namespace aperture::experiments
