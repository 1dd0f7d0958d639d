#include "experiments/control/control_monte_carlo_bench.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/bench/section_record.h"
#include "experiments/control/control_bench_sections.h"
#include "output/html_report.h"
#include "output/report_page.h"
#include "sim/control_params_io.h"
#include "sim/sim_params_io.h"

namespace aperture::experiments {
namespace {

class ControlMonteCarloBench : public MonteCarloBench {
 public:
  explicit ControlMonteCarloBench(const nlohmann::json& configuration) {
    nlohmann::json config;
    try {
      const nlohmann::json& o = configuration.at("options");
      options_.seed = o.at("seed").get<std::uint64_t>();
      options_.quick = o.at("quick").get<bool>();
      options_.recovery_trials = o.at("recovery_trials").get<int>();
      only_ = o.at("only").get<std::vector<std::string>>();
      config = configuration.at("config");
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(std::string("bench control configuration: ") + e.what());
    }
    sections_ = SelectControlBenchSections(only_);
    // JSON is YAML: the tree reads the recorded configuration as it reads a --config file.
    config::ConfigTree tree;
    if (!config.is_null()) tree.MergeYaml(config.dump(), "bench control configuration");
    ReadControlBenchVehicle(&tree, &options_);
    // The full effective vehicle and control stack (`--config OUT/summary.json` repeats them).
    configuration_ =
        ControlBenchConfiguration(options_, only_, nlohmann::json::parse(tree.ToJson()));
  }

  const nlohmann::json& configuration() const override { return configuration_; }

  TrialRange run() const override { return {0, static_cast<int>(sections_.size())}; }

  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    return RunTrialsInOrder(trials, threads, on_trial_done, [&](int k) {
      const ControlBenchSection& section = sections_.at(static_cast<std::size_t>(k));
      nlohmann::json record =
          RecordSection([&](nlohmann::json* summary, output::HtmlReport* report) {
            section.run(options_, summary, report);
          });
      record["section"] = section.key;
      return record;
    });
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    nlohmann::json& summary = out.summary();
    nlohmann::json keys = nlohmann::json::array();
    for (const auto& section : sections_) keys.push_back(section.key);
    summary["inputs"] = {{"seed", options_.seed},
                         {"quick", options_.quick},
                         {"recovery_trials", options_.recovery_trials},
                         {"sections", keys}};
    summary["config"] = configuration_["config"];
    output::HtmlReport report("aperture bench control");
    report.AddParagraph(
        "Control-stack comparisons of issue 4; the controllers model the nominal vehicle (rotor "
        "drag d_x = 0.5, d_y = 0.35 1/s, motor lag and kappa(f) of G.6.1), the IMU is noisy; "
        "seed " +
        std::to_string(options_.seed) +
        (options_.quick ? ", quick mode (shorter flights, fewer trials)" : ""));
    AddBenchVehicle(&summary, &report);
    for (const nlohmann::json& record : records) {
      AddSectionRecord(record, &summary, &report);
      summary["timing"][record.at("section").get<std::string>() + "_s"] = record["wall_time_s"];
    }
    // The sections compare controllers; their figures against the thesis are in each section.
    output::WriteReportPage(report,
                            {"done",
                             std::to_string(sections_.size()) +
                                 " section(s) of the control bench: " + keys.dump() + ".",
                             {}},
                            out);
    summary["outputs"] = {{"report", "report.html"}};
  }

  // summary["vehicle"] and a report section: is the simulated vehicle the model, the bounds of
  // its departures, and the bench vehicle drawn from the seed.
  void AddBenchVehicle(nlohmann::json* summary, output::HtmlReport* report) const {
    nlohmann::json& out = (*summary)["vehicle"];
    config::ConfigTree tree;
    tree.PutParams("vehicle", options_.vehicle);
    out = nlohmann::json::parse(tree.ToJson())["vehicle"];
    report->AddSection("Simulated vehicle (issue 21)");
    if (!options_.vehicle.mismatch) {
      report->AddParagraph(
          "vehicle.mismatch = false: the simulated vehicle is exactly the controllers' model "
          "(drag linear with their D, their thrust and torque maps and motor lag, no latency).");
      return;
    }
    tree.PutParams("drawn",
                   sim::DrawVehicleMismatch(options_.vehicle.mismatch_bounds, options_.seed));
    out["bench_vehicle"] = nlohmann::json::parse(tree.ToJson())["drawn"];
    report->AddParagraph(
        "vehicle.mismatch = true: the controllers keep the nominal model while the simulated "
        "vehicle departs from it within the bounds below (factors 1 + U(-b, b), additions "
        "U(0, max), latencies U(min, max)): drag factors on d_x, d_y, k_h, quadratic parasitic "
        "drag, rotor drag growing with thrust, motor time constants, thrust and torque maps, "
        "per-rotor fitness, battery sag, ESC delay, gyro vibration noise, command and estimate "
        "latency (not compensated). Every tracking and hover flight uses the bench vehicle drawn "
        "from the seed; each throw of the recovery section draws its own. " +
        std::string(options_.vehicle.hover_thrust_calibration
                        ? "The flight controller knows the collective thrust scale a hover "
                          "calibration (A.5.4) finds (vehicle.hover_thrust_calibration)."
                        : "No hover thrust calibration: the flight controller flies the nominal "
                          "thrust map."));
    report->AddTable(out["mismatch_bounds"], "vehicle.mismatch_bounds");
    report->AddTable(out["bench_vehicle"],
                     "bench vehicle (seed " + std::to_string(options_.seed) + ")");
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    return "aperture bench control: " + std::to_string(sections_.size()) + " section(s) " +
           summary["inputs"]["sections"].dump();
  }

 private:
  ControlBenchOptions options_;
  std::vector<std::string> only_;
  std::vector<ControlBenchSection> sections_;
  nlohmann::json configuration_;
};

}  // namespace

void ReadControlBenchVehicle(config::ConfigTree* tree, ControlBenchOptions* options) {
  config::ParamReader root = tree->Reader();
  root.ReadSection("control", &options->control);
  root.ReadSection("dynamics", &options->dynamics);
  root.ReadSection("imu", &options->imu);
  root.ReadSection("range", &options->range);
  root.ReadSection("vehicle", &options->vehicle);
  root.RejectUnknownKeys();
  tree->PutParams("control", options->control);
  tree->PutParams("dynamics", options->dynamics);
  tree->PutParams("imu", options->imu);
  tree->PutParams("range", options->range);
  tree->PutParams("vehicle", options->vehicle);
}

nlohmann::json ControlBenchConfiguration(const ControlBenchOptions& options,
                                         const std::vector<std::string>& only,
                                         const nlohmann::json& config) {
  return {{"options",
           {{"seed", options.seed},
            {"quick", options.quick},
            {"recovery_trials", options.recovery_trials},
            {"only", only}}},
          {"config", config}};
}

std::unique_ptr<MonteCarloBench> MakeControlMonteCarloBench(const nlohmann::json& configuration) {
  return std::make_unique<ControlMonteCarloBench>(configuration);
}

}  // namespace aperture::experiments
