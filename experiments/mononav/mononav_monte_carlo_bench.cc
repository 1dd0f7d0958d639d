#include "experiments/mononav/mononav_monte_carlo_bench.h"

#include <stdexcept>

#include "output/acceptance_outcome.h"
#include "output/html_report.h"
#include "output/report_page.h"

namespace aperture::experiments {
namespace {

class MononavMonteCarloBench : public MonteCarloBench {
 public:
  explicit MononavMonteCarloBench(const nlohmann::json& configuration) {
    try {
      const nlohmann::json& o = configuration.at("options");
      options_.trials = o.at("trials").get<int>();
      options_.first_seed = o.at("first_seed").get<std::uint64_t>();
      options_.duration_s = o.at("duration_s").get<double>();
      options_.quick = o.at("quick").get<bool>();
      options_.configurations = o.at("configurations").get<std::vector<std::string>>();
      options_.set_items = o.at("set_items").get<std::vector<std::string>>();
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(std::string("bench mononav configuration: ") + e.what());
    }
    options_.Validate();
    configuration_ = MononavBenchConfiguration(options_);
  }

  const nlohmann::json& configuration() const override { return configuration_; }

  TrialRange run() const override { return {0, options_.LayoutCount()}; }

  // One flight after another; `threads` bounds the renderer's parallelism.
  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    return RunTrialsInOrder(trials, threads, on_trial_done, [&](int k) {
      nlohmann::json flights = nlohmann::json::array();
      for (const MononavFlight& flight : FlyMononavLayout(options_, k)) {
        flights.push_back(MononavFlightToJson(flight));
      }
      return nlohmann::json{{"flights", flights}};
    });
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    std::vector<MononavFlight> flights;
    for (const nlohmann::json& record : records) {
      for (const nlohmann::json& flight : record.at("flights")) {
        flights.push_back(MononavFlightFromJson(flight));
      }
    }
    nlohmann::json& summary = out.summary();
    summary["inputs"] = {{"trials", options_.trials},
                         {"seed", options_.first_seed},
                         {"duration_s", options_.duration_s},
                         {"quick", options_.quick},
                         {"configurations", options_.configurations},
                         {"set", options_.set_items}};
    MononavBenchOptions options = options_;
    options.flights_csv_path = out.Path("flights.csv");
    output::HtmlReport report("aperture bench mononav");
    WriteMononavSections(options, flights, &summary, &report);
    output::WriteReportPage(report, output::AcceptanceOutcome(summary["acceptance"]), out);
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    std::string line = "aperture bench mononav: flights that reached the goal:";
    for (const auto& [configuration, row] : summary["success"].items()) {
      line += " " + configuration + " " + std::to_string(row["success"].get<int>()) + "/" +
              std::to_string(row["flights"].get<int>());
    }
    return line;
  }

 private:
  MononavBenchOptions options_;
  nlohmann::json configuration_;
};

}  // namespace

nlohmann::json MononavBenchConfiguration(const MononavBenchOptions& options) {
  return {{"options",
           {{"trials", options.trials},
            {"first_seed", options.first_seed},
            {"duration_s", options.duration_s},
            {"quick", options.quick},
            {"configurations", options.configurations},
            {"set_items", options.set_items}}}};
}

std::unique_ptr<MonteCarloBench> MakeMononavMonteCarloBench(const nlohmann::json& configuration) {
  return std::make_unique<MononavMonteCarloBench>(configuration);
}

}  // namespace aperture::experiments
