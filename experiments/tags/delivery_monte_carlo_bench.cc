#include "experiments/tags/delivery_monte_carlo_bench.h"

#include <stdexcept>
#include <string>

#include "output/acceptance_outcome.h"
#include "output/html_report.h"
#include "output/report_page.h"

namespace aperture::experiments {
namespace {

class DeliveryMonteCarloBench : public MonteCarloBench {
 public:
  explicit DeliveryMonteCarloBench(const nlohmann::json& configuration) {
    try {
      const nlohmann::json& o = configuration.at("options");
      options_.trials = o.at("trials").get<int>();
      options_.first_seed = o.at("first_seed").get<std::uint64_t>();
      options_.mission = o.at("mission").get<std::string>();
      options_.configurations = o.at("configurations").get<std::vector<std::string>>();
      options_.set_items = o.at("set_items").get<std::vector<std::string>>();
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(std::string("bench delivery configuration: ") + e.what());
    }
    options_.Validate();
    configuration_ = DeliveryBenchConfiguration(options_);
  }

  const nlohmann::json& configuration() const override { return configuration_; }

  TrialRange run() const override { return {0, options_.trials}; }

  // One flight after another; `threads` bounds the renderer's parallelism.
  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    return RunTrialsInOrder(trials, threads, on_trial_done, [&](int k) {
      nlohmann::json flights = nlohmann::json::array();
      for (const DeliveryFlight& flight : FlyDeliveryField(options_, k)) {
        flights.push_back(DeliveryFlightToJson(flight));
      }
      return nlohmann::json{{"flights", flights}};
    });
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    std::vector<DeliveryFlight> flights;
    for (const nlohmann::json& record : records) {
      for (const nlohmann::json& flight : record.at("flights")) {
        flights.push_back(DeliveryFlightFromJson(flight));
      }
    }
    nlohmann::json& summary = out.summary();
    summary["inputs"] = {{"trials", options_.trials},
                         {"seed", options_.first_seed},
                         {"mission", options_.mission},
                         {"configurations", options_.ConfigurationNames()},
                         {"set", options_.set_items}};
    DeliveryBenchOptions options = options_;
    options.flights_csv_path = out.Path("flights.csv");
    output::HtmlReport report("aperture bench delivery");
    WriteDeliverySections(options, flights, &summary, &report);
    output::WriteReportPage(report, output::AcceptanceOutcome(summary["acceptance"]), out);
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    const std::string first = options_.ConfigurationNames().front();
    const nlohmann::json& row = summary["delivery"][first];
    return "aperture bench delivery: " + std::to_string(row["success"].get<int>()) + "/" +
           std::to_string(row["flights"].get<int>()) + " fields with the kit on the goal (" +
           first + ")";
  }

 private:
  DeliveryBenchOptions options_;
  nlohmann::json configuration_;
};

}  // namespace

nlohmann::json DeliveryBenchConfiguration(const DeliveryBenchOptions& options) {
  return {{"options",
           {{"trials", options.trials},
            {"first_seed", options.first_seed},
            {"mission", options.mission},
            {"configurations", options.configurations},
            {"set_items", options.set_items}}}};
}

std::unique_ptr<MonteCarloBench> MakeDeliveryMonteCarloBench(const nlohmann::json& configuration) {
  return std::make_unique<DeliveryMonteCarloBench>(configuration);
}

}  // namespace aperture::experiments
