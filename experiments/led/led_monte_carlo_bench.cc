#include "experiments/led/led_monte_carlo_bench.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "output/acceptance_outcome.h"
#include "output/html_report.h"
#include "output/report_page.h"

namespace aperture::experiments {
namespace {

class LedMonteCarloBench : public MonteCarloBench {
 public:
  explicit LedMonteCarloBench(const nlohmann::json& configuration) {
    try {
      const nlohmann::json& o = configuration.at("options");
      options_.seed = o.at("seed").get<std::uint64_t>();
      options_.quick = o.at("quick").get<bool>();
      options_.only = o.at("only").get<std::vector<std::string>>();
      options_.calibration_errors = o.value("calibration_errors", false);
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(std::string("bench led configuration: ") + e.what());
    }
    sections_ = SelectedLedBenchSections(options_);
    configuration_ = LedBenchConfiguration(options_);
  }

  const nlohmann::json& configuration() const override { return configuration_; }

  TrialRange run() const override { return {0, static_cast<int>(sections_.size())}; }

  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    return RunTrialsInOrder(trials, threads, on_trial_done, [&](int k) {
      return RunLedBenchSection(sections_.at(static_cast<std::size_t>(k)), options_);
    });
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    nlohmann::json& summary = out.summary();
    summary["inputs"] = {
        {"seed", options_.seed}, {"quick", options_.quick}, {"only", options_.only},
        {"calibration_errors", options_.calibration_errors}};
    LedBenchOptions options = options_;
    options.frames_csv_path = out.Path("frames.csv");
    output::HtmlReport report("aperture bench led");
    WriteLedBenchOutputs(options, records, &summary, &report);
    output::WriteReportPage(report, output::AcceptanceOutcome(summary["acceptance"]), out);
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    return "aperture bench led: " + std::to_string(sections_.size()) + " section(s), " +
           output::AcceptanceOutcome(summary["acceptance"]).headline;
  }

 private:
  LedBenchOptions options_;
  std::vector<std::string> sections_;
  nlohmann::json configuration_;
};

}  // namespace

nlohmann::json LedBenchConfiguration(const LedBenchOptions& options) {
  return {{"options",
           {{"seed", options.seed},
            {"quick", options.quick},
            {"only", options.only},
            {"calibration_errors", options.calibration_errors}}}};
}

std::unique_ptr<MonteCarloBench> MakeLedMonteCarloBench(const nlohmann::json& configuration) {
  return std::make_unique<LedMonteCarloBench>(configuration);
}

}  // namespace aperture::experiments
