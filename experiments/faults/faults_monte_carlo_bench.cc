#include "experiments/faults/faults_monte_carlo_bench.h"

#include <stdexcept>

#include "experiments/missions/fly_mission.h"
#include "output/acceptance_outcome.h"
#include "output/html_report.h"
#include "output/report_page.h"

namespace aperture::experiments {
namespace {

class FaultsMonteCarloBench : public MonteCarloBench {
 public:
  explicit FaultsMonteCarloBench(const nlohmann::json& configuration) {
    try {
      options_ = FaultsBenchOptionsFromJson(configuration.at("options"));
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(std::string("bench faults configuration: ") + e.what());
    }
    configuration_ = FaultsBenchConfiguration(options_);
    // A bad scenario, mission key or --set item fails here, not as an error in every trial.
    MissionFlightSpec spec;
    spec.scenario = options_.scenario;
    spec.set_items = PlanFaultTrial(options_, 0).condition_items;
    spec.set_items.insert(spec.set_items.end(), options_.set_items.begin(),
                          options_.set_items.end());
    spec.duration_s = options_.duration_s;
    CheckMissionFlight(spec);
  }

  const nlohmann::json& configuration() const override { return configuration_; }

  TrialRange run() const override { return {0, options_.Trials()}; }

  // Flights side by side (each renders on the threads it gets); records in index order.
  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    return RunTrialsInParallel(trials, threads, on_trial_done,
                               [this](int k) { return FlyFaultTrial(options_, k); });
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    nlohmann::json& summary = out.summary();
    summary["inputs"] = FaultsBenchOptionsToJson(options_);
    output::HtmlReport report("aperture bench faults --mission " + options_.scenario);
    WriteFaultsBenchSections(options_, records, out.Path("flights.csv"), &summary, &report);
    summary["outputs"]["flights_csv"] = "flights.csv";
    output::WriteReportPage(report, output::AcceptanceOutcome(summary["acceptance"]), out);
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    const nlohmann::json& baseline = summary["baseline"];
    return "aperture bench faults --mission " + options_.scenario + ": baseline " +
           std::to_string(baseline["success"].get<int>()) + "/" +
           std::to_string(baseline["trials"].get<int>()) + " successful; " +
           output::AcceptanceOutcome(summary["acceptance"]).headline;
  }

 private:
  FaultsBenchOptions options_;
  nlohmann::json configuration_;
};

}  // namespace

nlohmann::json FaultsBenchConfiguration(const FaultsBenchOptions& options) {
  return {{"options", FaultsBenchOptionsToJson(options)}};
}

std::unique_ptr<MonteCarloBench> MakeFaultsMonteCarloBench(const nlohmann::json& configuration) {
  return std::make_unique<FaultsMonteCarloBench>(configuration);
}

}  // namespace aperture::experiments
