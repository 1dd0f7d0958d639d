// summary.json figures, flights.csv and the report sections of `aperture bench faults`.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "experiments/faults/faults_bench.h"
#include "output/csv_writer.h"
#include "output/svg_plot.h"

namespace aperture::experiments {
namespace {

constexpr double kMaxCrashRateAtTwice = 0.05;  // issue 18: crashes <= 5 % at twice the defaults
constexpr int kListedFailures = 30;

struct OutcomeCounts {
  int trials = 0, success = 0, safe_abort = 0, crash = 0;  // crash includes errors
  void Add(const std::string& outcome) {
    ++trials;
    if (outcome == "success") {
      ++success;
    } else if (outcome == "safe_abort") {
      ++safe_abort;
    } else {
      ++crash;
    }
  }
  double Rate(int count) const { return trials > 0 ? static_cast<double>(count) / trials : NAN; }
  nlohmann::json ToJson(double level) const {
    return {{"level", level},
            {"trials", trials},
            {"success", success},
            {"safe_abort", safe_abort},
            {"crash", crash},
            {"success_rate", Rate(success)},
            {"safe_abort_rate", Rate(safe_abort)},
            {"crash_rate", Rate(crash)}};
  }
};

// Counts per fault and level; the baseline under "none".
using CountsByLevel = std::map<double, OutcomeCounts>;

void WriteFaultFlightsCsv(const std::vector<nlohmann::json>& records, const std::string& path) {
  output::CsvWriter csv(
      path, {"trial", "repeat", "fault", "level", "seed", "outcome", "mission_passed",
             "sim_outcome", "sim_time_s", "wall_time_s", "reason", "mission_outcome", "condition", "replay"});
  for (const nlohmann::json& r : records) {
    std::string condition;
    for (const auto& item : r.at("condition")) {
      condition += (condition.empty() ? "" : " ") + item.get<std::string>();
    }
    csv.WriteCells(
        {static_cast<double>(r.at("trial").get<int>()),
         static_cast<double>(r.at("repeat").get<int>()), r.at("fault").get<std::string>(),
         r.at("level").get<double>(), std::to_string(r.at("seed").get<std::uint64_t>()),
         r.at("outcome").get<std::string>(), r.at("mission_passed").get<bool>() ? 1.0 : 0.0,
         r.at("sim_outcome").get<std::string>(), r.at("sim_time_s").get<double>(),
         r.at("wall_time_s").get<double>(), r.at("reason").get<std::string>(),
         r.at("mission_outcome").get<std::string>(), condition,
         r.at("replay").get<std::string>()});
  }
  csv.Close();
}

std::string CrashPercent(double rate) {
  if (!std::isfinite(rate)) return "-";
  return std::to_string(static_cast<int>(std::lround(100.0 * rate))) + " %";
}

}  // namespace

void WriteFaultsBenchSections(const FaultsBenchOptions& options,
                              const std::vector<nlohmann::json>& records,
                              const std::string& flights_csv_path, nlohmann::json* summary,
                              output::HtmlReport* report) {
  std::map<std::string, CountsByLevel> counts;
  OutcomeCounts baseline;
  nlohmann::json failures = nlohmann::json::array();
  for (const nlohmann::json& r : records) {
    const std::string fault = r.at("fault").get<std::string>();
    const std::string outcome = r.at("outcome").get<std::string>();
    if (fault == "none") {
      baseline.Add(outcome);
    } else {
      counts[fault][r.at("level").get<double>()].Add(outcome);
    }
    if (outcome != "success" && static_cast<int>(failures.size()) < kListedFailures) {
      failures.push_back({{"trial", r.at("trial")},
                          {"fault", fault},
                          {"level", r.at("level")},
                          {"outcome", outcome},
                          {"reason", r.at("reason")},
                          {"mission_outcome", r.at("mission_outcome")}});
    }
  }
  WriteFaultFlightsCsv(records, flights_csv_path);

  bool no_crash_at_default = baseline.crash == 0;
  bool few_crashes_at_twice = true;
  nlohmann::json faults = nlohmann::json::object();
  nlohmann::json acceptance_rows = nlohmann::json::array();
  report->AddSection("Outcome vs fault level");
  report->AddParagraph(
      "Each repeat flies one condition without a fault (level 0 of every plot) and with every "
      "fault at every level; success = the mission's own evaluation passed, safe abort = it did "
      "not but the vehicle ended hovering or resting, crash = a collision or an unstable end. "
      "Default level = the middle of the fault's range, twice = its top.");
  for (const FaultSpec& fault : options.SelectedFaults()) {
    CountsByLevel& by_level = counts[fault.name];
    nlohmann::json levels = nlohmann::json::array({baseline.ToJson(fault.low)});
    std::vector<double> x = {fault.low};
    std::vector<double> success = {100.0 * baseline.Rate(baseline.success)};
    std::vector<double> safe = {100.0 * baseline.Rate(baseline.safe_abort)};
    std::vector<double> crash = {100.0 * baseline.Rate(baseline.crash)};
    for (const auto& [level, c] : by_level) {
      levels.push_back(c.ToJson(level));
      x.push_back(level);
      success.push_back(100.0 * c.Rate(c.success));
      safe.push_back(100.0 * c.Rate(c.safe_abort));
      crash.push_back(100.0 * c.Rate(c.crash));
    }
    const OutcomeCounts& at_default = by_level[fault.DefaultLevel()];
    const OutcomeCounts& at_twice = by_level[fault.TwiceDefaultLevel()];
    no_crash_at_default &= at_default.trials > 0 && at_default.crash == 0;
    few_crashes_at_twice &=
        at_twice.trials > 0 && at_twice.Rate(at_twice.crash) <= kMaxCrashRateAtTwice;
    faults[fault.name] = {{"unit", fault.unit},
                          {"label", fault.label},
                          {"default_level", fault.DefaultLevel()},
                          {"twice_default_level", fault.TwiceDefaultLevel()},
                          {"levels", levels}};
    acceptance_rows.push_back(
        {{"fault", fault.name},
         {"default level", fault.DefaultLevel()},
         {"success / safe abort / crash at default",
          std::to_string(at_default.success) + " / " + std::to_string(at_default.safe_abort) +
              " / " + std::to_string(at_default.crash) + " of " +
              std::to_string(at_default.trials)},
         {"twice", fault.TwiceDefaultLevel()},
         {"success / safe abort / crash at twice",
          std::to_string(at_twice.success) + " / " + std::to_string(at_twice.safe_abort) + " / " +
              std::to_string(at_twice.crash) + " of " + std::to_string(at_twice.trials)},
         {"crash rate at twice", CrashPercent(at_twice.Rate(at_twice.crash))}});
    output::SvgPlot plot({fault.name + " (" + options.scenario + ")", fault.label, "flights [%]"});
    plot.AddLine("success", x, success).AddLine("safe abort", x, safe).AddLine("crash", x, crash);
    report->AddSvg(plot.Render());
  }
  report->AddSection("Default and twice the default level");
  report->AddTable(acceptance_rows);
  if (!failures.empty()) {
    report->AddSection("Flights that did not succeed (first " + std::to_string(kListedFailures) +
                       ")");
    report->AddTable(failures);
  }

  (*summary)["baseline"] = baseline.ToJson(0.0);
  (*summary)["faults"] = faults;
  (*summary)["failures"] = failures;
  (*summary)["acceptance"] = {
      {"no crash at the default fault levels (baseline included)", no_crash_at_default},
      {"crashes <= 5 % at twice the default levels", few_crashes_at_twice}};
}

}  // namespace aperture::experiments
