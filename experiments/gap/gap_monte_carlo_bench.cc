#include "experiments/gap/gap_monte_carlo_bench.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "experiments/gap/gap_mission_trial.h"
#include "experiments/gap/gap_trial_record_json.h"
#include "experiments/gap/ground_truth_gap_autopilot.h"

namespace aperture::experiments {
namespace {

// "; detector: ..." for a run with detector sequences, else "".
std::string DescribeDetector(const nlohmann::json& summary) {
  if (!summary.contains("detector")) return "";
  const nlohmann::json& d = summary["detector"];
  const auto number = [&](const char* key, double scale, const char* format) {
    if (!d[key].is_number()) return std::string("n/a");
    char text[32];
    std::snprintf(text, sizeof(text), format, scale * d[key].get<double>());
    return std::string(text);
  };
  return "; detector: " + number("detection_rate", 100.0, "%.1f %%") + " of " +
         std::to_string(d["frames_in_view"].get<int>()) + " frames in view, rotation median " +
         number("rotation_error_median_deg", 1.0, "%.3f deg") + ", T_GC " +
         number("T_GC_position_error_median_pct", 1.0, "%.3f %%") + ", T_CG " +
         number("T_CG_position_error_median_pct", 1.0, "%.3f %%") + " of the distance";
}

// A trial's record holds the paper configuration's flight of the same draws under this key.
constexpr const char* kPaperFlightKey = "paper_configuration";

// "; Table I (planned t_c, all trials): ours mean |position error| [...] m, paper ..." .
std::string DescribeTableI(const nlohmann::json& summary) {
  std::string text = "; Table I (planned t_c, all trials): mean |position error|";
  for (const auto& [name, figures] : summary["table_i"].items()) {
    if (!figures.is_object()) continue;
    text += " " + name + " " + figures["position_mean"].dump() + " m (" +
            std::to_string(figures["successes"].get<int>()) + "/" +
            std::to_string(figures["trials"].get<int>()) + " successful)";
  }
  return text;
}

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

  // The flights, then the detector sequences.
  TrialRange run() const override {
    return {options_.first_trial, options_.trials + options_.detector_sequences};
  }

  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    const int first_sequence = options_.first_trial + options_.trials;
    const int end = trials.first + trials.count;
    std::vector<nlohmann::json> records;
    const TrialRange flights{trials.first,
                             std::max(0, std::min(end, first_sequence) - trials.first)};
    if (flights.count > 0) {
      GapBenchOptions options = options_;
      options.first_trial = flights.first;
      options.trials = flights.count;
      options.detector_sequences = 0;  // run below, as the trials of this range that follow
      options.threads = threads;
      const GapBenchResult result = RunGapBench(options, setup_, factory_, on_trial_done);
      // One record per trial (the run counts them): the paper configuration's flight inside it.
      for (std::size_t i = 0; i < result.trials.size(); ++i) {
        records.push_back(GapTrialRecordToJson(result.trials[i]));
        if (i < result.paper_trials.size()) {
          records.back()[kPaperFlightKey] = GapTrialRecordToJson(result.paper_trials[i]);
        }
      }
      if (static_cast<int>(result.trials.size()) < flights.count) return records;  // interrupted
    }
    const int flown = flights.count;
    const int sequences_first = std::max(trials.first, first_sequence);
    const TrialRange sequences{sequences_first, end - sequences_first};
    if (sequences.count <= 0) return records;
    std::vector<nlohmann::json> sequence_records = RunTrialsInParallel(
        sequences, threads,
        [&](int done) {
          if (on_trial_done) on_trial_done(flown + done);
        },
        [&](int k) {
          return GapDetectorSequenceRecordToJson(
              RunGapBenchDetectorSequence(options_, setup_, k - first_sequence));
        });
    for (nlohmann::json& record : sequence_records) records.push_back(std::move(record));
    return records;
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    GapBenchResult result;
    result.options = options_;
    result.mission = setup_.mission;
    result.scenario_config = setup_.scenario_config;
    for (const nlohmann::json& record : records) {
      if (record.contains("detector_sequence")) {
        result.detector_sequences.push_back(GapDetectorSequenceRecordFromJson(record));
        continue;
      }
      result.trials.push_back(GapTrialRecordFromJson(record));
      if (record.contains(kPaperFlightKey)) {
        result.paper_trials.push_back(GapTrialRecordFromJson(record[kPaperFlightKey]));
      }
      // As RunGapBench: the autopilot of the first trial that ran.
      if (result.autopilot_name.empty())
        result.autopilot_name = result.trials.back().autopilot_name;
    }
    WriteGapBenchOutputs(result, out);
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    const nlohmann::json& error = summary["error_at_gap"];
    return "aperture bench gap (" + summary["inputs"]["autopilot"].get<std::string>() +
           "): " + std::to_string(summary["successes"].get<int>()) + "/" +
           std::to_string(summary["trials"].get<int>()) +
           " successful, mean |position error| at the gap " + error["position_mean"].dump() +
           " m over " + std::to_string(error["trials"].get<int>()) + " crossings" +
           DescribeTableI(summary) + DescribeDetector(summary);
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
  // The ground-truth autopilot has no lead-in: the paper's configuration would fly the same.
  effective.paper_configuration = options.paper_configuration && autopilot != "ground_truth";
  return {{"autopilot", autopilot}, {"options", GapBenchOptionsToJson(effective)}};
}

std::unique_ptr<MonteCarloBench> MakeGapMonteCarloBench(const nlohmann::json& configuration) {
  return std::make_unique<GapMonteCarloBench>(configuration);
}

}  // namespace aperture::experiments
