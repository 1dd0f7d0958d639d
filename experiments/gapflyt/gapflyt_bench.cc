#include "experiments/gapflyt/gapflyt_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>

#include "config/config_tree.h"
#include "experiments/gapflyt/tight_opening.h"
#include "experiments/missions/builtin_missions.h"
#include "experiments/ts2p/ts2p_scan.h"
#include "output/csv_writer.h"
#include "output/html_report.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_sitl.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {
namespace {

// Horizontal span of the default vehicle: the rotor disks' outer edges (X configuration).
double VehicleSpanM() {
  const control::VehicleParameters vehicle;
  const sim::CollisionParams collision;
  return 2.0 * (vehicle.arm_length_m / std::sqrt(2.0) + collision.propeller_radius_m);
}

// The `gapflyt` scenario of a trial.
sim::ScenarioParams TrialScenarioParams(const GapflytBenchOptions& options,
                                        const GapflytTrialConfig& config) {
  sim::ScenarioParams params = sim::LoadScenarioParams(sim::ScenarioConfig("gapflyt"));
  params.seed = config.scene_seed;
  params.cameras.front().second.width = options.width;
  params.cameras.front().second.height = options.height;
  params.gapflyt.shape = config.shape;
  params.gapflyt.size_m = config.size_m;
  params.gapflyt.center_m = config.center_m;
  params.gapflyt.foreground_x_m = config.foreground_x_m;
  params.gapflyt.background_x_m = config.background_x_m;
  return params;
}

double Figure(const nlohmann::json& figures, const char* key) {
  return figures.contains(key) && figures[key].is_number()
             ? figures[key].get<double>()
             : std::numeric_limits<double>::quiet_NaN();
}

nlohmann::json Stats(const std::vector<double>& values) {
  if (values.empty()) return nullptr;
  double sum = 0.0;
  for (double v : values) sum += v;
  return {{"mean", sum / values.size()},
          {"min", *std::min_element(values.begin(), values.end())},
          {"max", *std::max_element(values.begin(), values.end())},
          {"count", values.size()}};
}

std::string Percent(double rate) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.0f %%", 100.0 * rate);
  return buffer;
}

}  // namespace

void GapflytBenchOptions::Validate() const {
  if (trials < 1) throw std::invalid_argument("bench gapflyt: --trials must be >= 1");
  if (laws.empty()) throw std::invalid_argument("bench gapflyt: no servo law to fly");
  for (const std::string& law : laws) {
    if (law != "moments" && law != "pid") {
      throw std::invalid_argument("bench gapflyt: unknown servo law '" + law + "' (moments | pid)");
    }
  }
  if (tight_every < 0 || !(tight_margin_m >= 0.0) || width < 32 || height < 24 ||
      !(duration_s > 0.0)) {
    throw std::invalid_argument(
        "bench gapflyt: tight_every must be >= 0, tight_margin_m >= 0, the image at least 32 x "
        "24 and duration_s > 0");
  }
}

GapflytTrialConfig DrawGapflytTrial(const GapflytBenchOptions& options, int trial) {
  std::seed_seq sequence{static_cast<std::uint32_t>(options.seed),
                         static_cast<std::uint32_t>(options.seed >> 32),
                         static_cast<std::uint32_t>(trial), 0x67666c74u /* "gflt" */};
  std::mt19937_64 rng(sequence);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](const Eigen::Vector2d& range) {
    return range.x() + (range.y() - range.x()) * unit(rng);
  };
  const GapflytTrialRanges& r = options.ranges;
  GapflytTrialConfig config;
  config.trial = trial;
  config.shape = kTs2pShapes[static_cast<std::size_t>(trial) % kTs2pShapes.size()];
  config.scene_seed = rng();
  config.foreground_x_m = uniform(r.foreground_x_m);
  config.background_x_m = uniform(r.background_x_m);
  config.size_m = Eigen::Vector2d(uniform(r.width_m), uniform(r.height_m));
  config.center_m = Eigen::Vector2d(uniform({-r.max_offset_m, r.max_offset_m}),
                                    1.5 + uniform({-r.max_offset_m, r.max_offset_m}));
  const int round = trial / static_cast<int>(kTs2pShapes.size());
  config.tight = options.tight_every > 0 && round % options.tight_every == options.tight_every - 1;
  if (config.tight) {
    // The narrowest passage tight_margin_m wider than the vehicle, for this shape and its corners.
    const sim::Scenario scenario = sim::BuildScenario(TrialScenarioParams(options, config));
    config.size_m.x() = TightOpeningWidthM(OpeningFromScene(scenario.scene()), config.size_m.x(),
                                           BenchFootprint(), options.tight_margin_m);
  }
  return config;
}

std::string GapflytTrialSimCommand(const GapflytBenchOptions& options,
                                   const GapflytTrialConfig& config, const std::string& law) {
  char numbers[320];
  std::snprintf(numbers, sizeof(numbers),
                " --set 'gapflyt.size_m=[%.17g, %.17g]' --set 'gapflyt.center_m=[%.17g, %.17g]'"
                " --set gapflyt.foreground_x_m=%.17g --set gapflyt.background_x_m=%.17g",
                config.size_m.x(), config.size_m.y(), config.center_m.x(), config.center_m.y(),
                config.foreground_x_m, config.background_x_m);
  std::string command = "aperture sim gapflyt --seed " + std::to_string(config.scene_seed) +
                        " --duration " + std::to_string(options.duration_s) +
                        " --set gapflyt.shape=" + config.shape + numbers +
                        " --set cameras.front.width=" + std::to_string(options.width) +
                        " --set cameras.front.height=" + std::to_string(options.height) +
                        " --set mission.servo.law=" + law;
  for (const std::string& item : options.mission_set_items) command += " --set '" + item + "'";
  return command + " --out trial" + std::to_string(config.trial) + "-" + law;
}

GapflytTrialRecord RunGapflytTrial(const GapflytBenchOptions& options,
                                   const GapflytTrialConfig& config, const std::string& law) {
  const auto start = std::chrono::steady_clock::now();
  GapflytTrialRecord record;
  record.config = config;
  record.law = law;
  try {
    sim::Scenario scenario = sim::BuildScenario(TrialScenarioParams(options, config));
    sim::SitlRunnerParams sitl;
    sitl.duration_s = options.duration_s;
    sitl.trajectory_decimation = 2;  // 500 Hz ground truth: the crossing to ~1 mm at 1 m/s
    sim::ConfigureSitlFromScenario(scenario, &sitl);
    for (sim::SitlCamera& camera : sitl.cameras) camera.render.ground_truth = false;
    sitl.SetSeed(config.scene_seed);

    MissionRegistry missions;
    RegisterBuiltinMissions(missions);
    std::vector<std::string> set_items = options.mission_set_items;
    set_items.push_back("mission.servo.law=" + law);
    const config::ConfigTree tree = config::ConfigTree::FromCommandLine("", {}, set_items);
    config::ParamReader root = tree.Reader();
    config::ParamReader mission_params = root.Section("mission");
    std::unique_ptr<MissionFlight> flight =
        missions.Create("gapflyt", {scenario, sitl, mission_params});
    root.RejectUnknownKeys();
    sim::SitlRunner runner(sitl, &scenario.scene());
    const sim::SitlResult result =
        runner.Run(flight->autopilot(), sim::MakeScenarioHooks(&scenario));
    const MissionEvaluation evaluation = flight->Evaluate(result);
    record.passed = evaluation.passed;
    record.figures = evaluation.figures;
    record.sim_time_s = result.sim_time_s;
    const nlohmann::json& detection = record.figures["detection"];
    record.seed002_success =
        record.passed && detection.is_object() && detection.value("detected", false);
  } catch (const std::exception& e) {
    record.passed = false;
    record.figures["failure_reason"] = std::string("error: ") + e.what();
  }
  record.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return record;
}

nlohmann::json SummarizeGapflytBench(const GapflytBenchResult& result) {
  nlohmann::json summary;
  summary["trials_per_law"] = result.options.trials;
  summary["seed"] = result.options.seed;
  summary["image"] = {result.options.width, result.options.height};
  summary["vehicle_span_m"] = VehicleSpanM();
  summary["tight_margin_m"] = result.options.tight_margin_m;
  nlohmann::json laws;
  nlohmann::json per_trial = nlohmann::json::array();
  for (const std::string& law : result.options.laws) {
    int n = 0, passed = 0, seed002 = 0, tight = 0, tight_passed = 0;
    std::vector<double> clearance, time_to_cross, offset, overlap;
    std::map<std::string, std::pair<int, int>> shapes;  // passed, trials
    std::map<std::string, int> failures;
    for (const GapflytTrialRecord& t : result.trials) {
      if (t.law != law) continue;
      ++n;
      passed += t.passed;
      seed002 += t.seed002_success;
      if (t.config.tight) {
        ++tight;
        tight_passed += t.passed;
      }
      shapes[t.config.shape].first += t.passed;
      shapes[t.config.shape].second += 1;
      if (!t.passed) failures[t.figures.value("failure_reason", std::string("unknown"))] += 1;
      if (t.passed) {
        clearance.push_back(Figure(t.figures, "clearance_m"));
        time_to_cross.push_back(Figure(t.figures, "time_to_cross_s"));
        offset.push_back(Figure(t.figures, "crossing_offset_norm_m"));
      }
      if (t.figures.contains("detection") && t.figures["detection"].contains("overlap")) {
        overlap.push_back(t.figures["detection"]["overlap"].get<double>());
      }
      per_trial.push_back({{"law", law},
                           {"trial", t.config.trial},
                           {"shape", t.config.shape},
                           {"tight", t.config.tight},
                           {"scene_seed", t.config.scene_seed},
                           {"passed", t.passed},
                           {"seed002_success", t.seed002_success},
                           {"figures", t.figures},
                           {"reproduce", GapflytTrialSimCommand(result.options, t.config, law)}});
    }
    nlohmann::json per_shape;
    for (const auto& [shape, counts] : shapes) {
      per_shape[shape] = {{"passed", counts.first},
                          {"trials", counts.second},
                          {"success_rate", double(counts.first) / counts.second}};
    }
    laws[law] = {{"trials", n},
                 {"passed", passed},
                 {"success_rate", n ? double(passed) / n : 0.0},
                 {"seed002_success_rate", n ? double(seed002) / n : 0.0},
                 {"tight_trials", tight},
                 {"tight_success_rate",
                  tight ? nlohmann::json(double(tight_passed) / tight) : nlohmann::json(nullptr)},
                 {"per_shape", per_shape},
                 {"failures", failures},
                 {"clearance_m", Stats(clearance)},
                 {"time_to_cross_s", Stats(time_to_cross)},
                 {"crossing_offset_m", Stats(offset)},
                 {"detection_overlap", Stats(overlap)}};
  }
  summary["laws"] = laws;
  summary["per_trial"] = per_trial;
  return summary;
}

void WriteGapflytBenchOutputs(const GapflytBenchResult& result, output::OutputFolder& out) {
  const nlohmann::json summary = SummarizeGapflytBench(result);
  for (const auto& [key, value] : summary.items()) out.summary()[key] = value;
  {
    output::CsvWriter csv(
        out.Path("trials.csv"),
        {"law", "trial", "shape", "tight", "width_m", "height_m", "foreground_x_m",
         "background_x_m", "passed", "seed002_success", "clearance_m", "crossing_offset_m",
         "time_to_cross_s", "detection_overlap", "failure_reason", "wall_time_s"});
    for (const GapflytTrialRecord& t : result.trials) {
      const nlohmann::json& d =
          t.figures.contains("detection") ? t.figures["detection"] : nlohmann::json::object();
      csv.WriteCells({t.law, double(t.config.trial), t.config.shape, t.config.tight ? 1.0 : 0.0,
                      t.config.size_m.x(), t.config.size_m.y(), t.config.foreground_x_m,
                      t.config.background_x_m, t.passed ? 1.0 : 0.0, t.seed002_success ? 1.0 : 0.0,
                      Figure(t.figures, "clearance_m"), Figure(t.figures, "crossing_offset_norm_m"),
                      Figure(t.figures, "time_to_cross_s"),
                      d.contains("overlap") ? d["overlap"].get<double>()
                                            : std::numeric_limits<double>::quiet_NaN(),
                      t.figures.value("failure_reason", std::string()), t.wall_time_s});
    }
  }
  output::HtmlReport report("aperture bench gapflyt");
  std::vector<output::ReportFigure> figures;
  bool all_pass = true;
  for (const std::string& law : result.options.laws) {
    const nlohmann::json& l = summary["laws"][law];
    figures.push_back({law + " success", Percent(l["success_rate"].get<double>()), ">= 90 %"});
    all_pass &= l["success_rate"].get<double>() >= 0.9;
  }
  report.AddOutcome({all_pass ? "passed" : "failed",
                     "GapFlyt closed-loop success over " + std::to_string(result.options.trials) +
                         " randomized trials per servo law (seed 002 Sec. IV analog)",
                     figures});
  report.AddRunDescription(out.summary(), out.ElapsedSeconds());
  report.AddSection("Success per shape and servo law");
  nlohmann::json table = nlohmann::json::array();
  for (const std::string& law : result.options.laws) {
    const nlohmann::json& l = summary["laws"][law];
    nlohmann::json row = {{"law", law}};
    for (const auto& [shape, s] : l["per_shape"].items()) {
      row[shape] =
          std::to_string(s["passed"].get<int>()) + "/" + std::to_string(s["trials"].get<int>());
    }
    row["all"] = Percent(l["success_rate"].get<double>());
    row["seed 002 (+ >= 75 % overlap)"] = Percent(l["seed002_success_rate"].get<double>());
    row["tight"] = l["tight_success_rate"].is_null()
                       ? std::string("-")
                       : Percent(l["tight_success_rate"].get<double>());
    table.push_back(row);
  }
  report.AddTable(table,
                  "Passed / flown per shape; tight: the narrowest passage (the level "
                  "vehicle's best placement) is " +
                      std::to_string(result.options.tight_margin_m) + " m wider than the vehicle");
  nlohmann::json figures_table = nlohmann::json::array();
  for (const std::string& law : result.options.laws) {
    const nlohmann::json& l = summary["laws"][law];
    figures_table.push_back({{"law", law},
                             {"clearance_m", l["clearance_m"]},
                             {"crossing_offset_m", l["crossing_offset_m"]},
                             {"time_to_cross_s", l["time_to_cross_s"]},
                             {"detection_overlap", l["detection_overlap"]},
                             {"failures", l["failures"]}});
  }
  report.AddTable(figures_table,
                  "Figures of the successful crossings (clearance: the rotor "
                  "disks and body to the opening's edge) and the failures");
  report.AddCollapsedTable(out.summary(), "Every figure of summary.json");
  report.Write(out.Path("report.html"));
}

}  // namespace aperture::experiments
