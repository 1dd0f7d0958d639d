#include "experiments/gap/gap_monte_carlo_bench.h"

#include <stdexcept>

#include "experiments/gap/gap_mission_trial.h"
#include "experiments/gap/gap_trial_record_json.h"
#include "experiments/gap/ground_truth_gap_autopilot.h"

namespace aperture::experiments {
namespace {

class GapMonteCarloBench : public MonteCarloBench {
 public:
  explicit GapMonteCarloBench(const nlohmann::json& configuration) {
    if (!configuration.is_object() || !configuration.contains("autopilot") ||
        !configuration.contains("options")) {
      throw std::invalid_argument(
          "bench gap configuration: expected an object with \"autopilot\" and \"options\"");
    }
    autopilot_ = configuration["autopilot"].get<std::string>();
    if (autopilot_ == "mission") {
      factory_ = MakeGapMissionTrialFactory();
    } else if (autopilot_ == "ground_truth") {
      factory_ = MakeGroundTruthGapAutopilotFactory();
    } else {
      throw std::invalid_argument("bench gap configuration: autopilot '" + autopilot_ +
                                  "' (mission | ground_truth)");
    }
    options_ = GapBenchOptionsFromJson(configuration["options"]);
    setup_ = PrepareGapBench(options_);
    configuration_ = GapBenchConfiguration(options_, autopilot_);
    configuration_["config"] = setup_.scenario_config;
  }

  const nlohmann::json& configuration() const override { return configuration_; }

  TrialRange run() const override { return {options_.first_trial, options_.trials}; }

  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    GapBenchOptions options = options_;
    options.first_trial = trials.first;
    options.trials = trials.count;
    options.threads = threads;
    const GapBenchResult result = RunGapBench(options, setup_, factory_, on_trial_done);
    std::vector<nlohmann::json> records;
    records.reserve(result.trials.size());
    for (const GapTrialRecord& record : result.trials) {
      records.push_back(GapTrialRecordToJson(record));
    }
    return records;
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    GapBenchResult result;
    result.options = options_;
    result.mission = setup_.mission;
    result.scenario_config = setup_.scenario_config;
    for (const nlohmann::json& record : records) {
      result.trials.push_back(GapTrialRecordFromJson(record));
      // As RunGapBench: the autopilot of the first trial that ran.
      if (result.autopilot_name.empty()) result.autopilot_name = result.trials.back().autopilot_name;
    }
    WriteGapBenchOutputs(result, out);
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    const nlohmann::json& error = summary["error_at_gap"];
    return "aperture bench gap (" + summary["inputs"]["autopilot"].get<std::string>() + "): " +
           std::to_string(summary["successes"].get<int>()) + "/" +
           std::to_string(summary["trials"].get<int>()) +
           " successful, mean |position error| at the gap " + error["position_mean"].dump() +
           " m over " + std::to_string(error["trials"].get<int>()) + " crossings";
  }

 private:
  std::string autopilot_;
  GapTrialAutopilotFactory factory_;
  GapBenchOptions options_;
  GapBenchSetup setup_;
  nlohmann::json configuration_;
};

}  // namespace

nlohmann::json GapBenchConfiguration(const GapBenchOptions& options, const std::string& autopilot) {
  GapBenchOptions effective = options;
  effective.render_cameras = autopilot != "ground_truth";  // ground truth needs no camera
  return {{"autopilot", autopilot}, {"options", GapBenchOptionsToJson(effective)}};
}

std::unique_ptr<MonteCarloBench> MakeGapMonteCarloBench(const nlohmann::json& configuration) {
  return std::make_unique<GapMonteCarloBench>(configuration);
}

}  // namespace aperture::experiments
