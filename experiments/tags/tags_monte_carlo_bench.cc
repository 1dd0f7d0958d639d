#include "experiments/tags/tags_monte_carlo_bench.h"

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "output/html_report.h"

namespace aperture::experiments {
namespace {

class TagsMonteCarloBench : public MonteCarloBench {
 public:
  TagsMonteCarloBench(const nlohmann::json& configuration,
                      const perception::TagDetectorRegistry& detectors) {
    std::vector<std::string> names;
    try {
      const nlohmann::json& o = configuration.at("options");
      options_.seed = o.at("seed").get<std::uint64_t>();
      options_.quick = o.at("quick").get<bool>();
      names = o.at("detectors").get<std::vector<std::string>>();
      options_.sections = o.at("sections").get<std::vector<std::string>>();
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(std::string("bench tags configuration: ") + e.what());
    }
    options_.detectors = detectors;
    if (names != detectors.Names()) {
      throw std::invalid_argument("bench tags configuration: detectors " +
                                  nlohmann::json(names).dump() + ", this build has " +
                                  nlohmann::json(detectors.Names()).dump());
    }
    sections_ = SelectedTagBenchSections(options_);
    configuration_ = TagsBenchConfiguration(options_);
  }

  const nlohmann::json& configuration() const override { return configuration_; }

  TrialRange run() const override { return {0, static_cast<int>(sections_.size())}; }

  std::vector<nlohmann::json> RunTrials(
      const TrialRange& trials, int threads,
      const std::function<void(int)>& on_trial_done) const override {
    return RunTrialsInOrder(trials, threads, on_trial_done, [&](int k) {
      return RunTagBenchSection(sections_.at(static_cast<std::size_t>(k)), options_);
    });
  }

  void WriteOutputs(const std::vector<nlohmann::json>& records,
                    output::OutputFolder& out) const override {
    nlohmann::json& summary = out.summary();
    summary["inputs"] = {
        {"seed", options_.seed}, {"quick", options_.quick}, {"sections", sections_}};
    TagBenchOptions options = options_;
    options.frames_csv_path = out.Path("frames.csv");
    options.observations_csv_path = out.Path("observations.csv");
    output::HtmlReport report("aperture bench tags");
    WriteTagBenchOutputs(options, records, &summary, &report);
    report.Write(out.Path("report.html"));
  }

  std::string DescribeOutcome(const nlohmann::json& summary) const override {
    std::string outcome = "aperture bench tags:";
    if (summary.contains("mapping")) {
      outcome +=
          " map RMS after optimization " + summary["mapping"]["map_rms_after_m"].dump() + " m,";
    }
    if (summary.contains("missions")) {
      outcome += " missions solved " + summary["missions"]["solve_rate"].dump() + ",";
    }
    return outcome + " acceptance " + summary.value("acceptance", nlohmann::json::object()).dump();
  }

 private:
  TagBenchOptions options_;
  std::vector<std::string> sections_;  // run order
  nlohmann::json configuration_;
};

}  // namespace

nlohmann::json TagsBenchConfiguration(const TagBenchOptions& options) {
  return {{"options",
           {{"seed", options.seed},
            {"quick", options.quick},
            {"detectors", options.detectors.Names()},
            {"sections", options.sections}}}};
}

MonteCarloBenchFactory MakeTagsMonteCarloBenchFactory(perception::TagDetectorRegistry detectors) {
  return [detectors = std::move(detectors)](const nlohmann::json& configuration) {
    return std::unique_ptr<MonteCarloBench>(
        std::make_unique<TagsMonteCarloBench>(configuration, detectors));
  };
}

}  // namespace aperture::experiments
