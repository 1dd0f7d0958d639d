#include "experiments/tags/delivery_bench.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <stdexcept>

#include "control/constants.h"
#include "experiments/bench/sample_statistics.h"
#include "output/csv_writer.h"
#include "output/svg_plot.h"

namespace aperture::experiments {
namespace {

constexpr const char* kRelocalize = "relocalize";
constexpr const char* kOpenLoop = "open_loop";
// The acceptance: the kit on the goal in >= 95 % of the fields, with relocalization.
constexpr double kSuccessTargetPercent = 95.0;

// The finite values of a sample (flights without a figure leave NaN).
std::vector<double> FiniteValues(const std::vector<double>& values) {
  std::vector<double> finite;
  std::copy_if(values.begin(), values.end(), std::back_inserter(finite),
               [](double v) { return std::isfinite(v); });
  return finite;
}

double MaxFinite(const std::vector<double>& values) {
  const std::vector<double> finite = FiniteValues(values);
  return finite.empty() ? control::kNaN : *std::max_element(finite.begin(), finite.end());
}

double Figure(const DeliveryFlight& flight, const char* key) {
  const nlohmann::json& figures = flight.run.evaluation.figures;
  return figures.contains(key) && figures[key].is_number() ? figures[key].get<double>()
                                                           : control::kNaN;
}

// The first reason, in the order the mission's Evaluate checks them (tag_follow_flight.cc).
std::string FailureOf(const MissionFlightRun& run) {
  if (run.evaluation.passed) return "";
  const nlohmann::json& f = run.evaluation.figures;
  if (f.contains("plan_failure")) return "mapping";
  if (f.value("collision", false)) return "quadrotor_collision";
  if (f.contains("robot_contact") && !f["robot_contact"].is_null()) return "robot_contact";
  if (f.value("robot_state", std::string()) == "fail_safe") return "fail_safe";
  if (!f.value("robot_mission_executed", false)) return "not_finished";
  if (!f.value("kit_on_goal", false)) return "kit_off_goal";
  return "servo_offset";
}

std::vector<const DeliveryFlight*> Of(const std::vector<DeliveryFlight>& flights,
                                      const std::string& configuration) {
  std::vector<const DeliveryFlight*> out;
  for (const DeliveryFlight& f : flights) {
    if (f.configuration == configuration) out.push_back(&f);
  }
  return out;
}

nlohmann::json ConfigurationRow(const std::vector<const DeliveryFlight*>& flights) {
  int success = 0;
  std::map<std::string, std::vector<std::uint64_t>> failures;
  std::vector<double> max_offsets, fix_errors, corrections, removals;
  for (const DeliveryFlight* f : flights) {
    if (f->failure.empty()) {
      ++success;
    } else {
      failures[f->failure].push_back(f->seed);
    }
    max_offsets.push_back(Figure(*f, "max_offset_of_width"));
    fix_errors.push_back(Figure(*f, "relocalization_max_fix_error_m"));
    corrections.push_back(Figure(*f, "relocalization_max_correction_m"));
    const nlohmann::json& order = f->run.evaluation.figures["robot_removals"];
    removals.push_back(order.is_array() ? static_cast<double>(order.size()) : control::kNaN);
  }
  // A field on which no order of removals reaches the goal has no mission to execute: the
  // planner's statistic (bench tags --section missions), not the execution's.
  const int without_mission =
      failures.count("no_mission") ? static_cast<int>(failures["no_mission"].size()) : 0;
  const int n = static_cast<int>(flights.size()) - without_mission;
  nlohmann::json row;
  row["success_rate_percent"] = n > 0 ? 100.0 * success / n : 0.0;
  row["success"] = success;
  row["flights"] = n;
  row["fields_without_mission"] = without_mission;
  row["failures_by_cause"] = nlohmann::json::object();
  for (const auto& [cause, seeds] : failures) row["failures_by_cause"][cause] = seeds;
  row["max_offset_of_width"] = FiniteOrNull(MaxFinite(max_offsets));
  row["median_max_offset_of_width"] = FiniteOrNull(UpperMedian(FiniteValues(max_offsets)));
  row["relocalization_max_fix_error_m"] = FiniteOrNull(MaxFinite(fix_errors));
  row["relocalization_max_correction_m"] = FiniteOrNull(MaxFinite(corrections));
  row["removals_mean"] = FiniteOrNull(Mean(FiniteValues(removals)));
  return row;
}

void WriteFlightsCsv(const std::vector<DeliveryFlight>& flights, const std::string& path) {
  output::CsvWriter csv(
      path, {"configuration", "seed", "success", "failure", "removals", "robot_mission_s",
             "max_offset_of_width", "kit_from_goal_m", "relocalizations",
             "relocalization_max_correction_m", "relocalization_max_fix_error_m", "map_rms_after_m",
             "sim_time_s", "wall_time_s"});
  for (const DeliveryFlight& f : flights) {
    const nlohmann::json& order = f.run.evaluation.figures["robot_removals"];
    csv.WriteCells({output::CsvCell(f.configuration), output::CsvCell(double(f.seed)),
                    output::CsvCell(double(f.failure.empty())), output::CsvCell(f.failure),
                    output::CsvCell(order.is_array() ? double(order.size()) : control::kNaN),
                    output::CsvCell(Figure(f, "robot_mission_s")),
                    output::CsvCell(Figure(f, "max_offset_of_width")),
                    output::CsvCell(Figure(f, "kit_from_goal_m")),
                    output::CsvCell(Figure(f, "relocalizations")),
                    output::CsvCell(Figure(f, "relocalization_max_correction_m")),
                    output::CsvCell(Figure(f, "relocalization_max_fix_error_m")),
                    output::CsvCell(Figure(f, "map_rms_after_m")),
                    output::CsvCell(f.run.sim_time_s), output::CsvCell(f.run.wall_time_s)});
  }
  csv.Close();
}

}  // namespace

void DeliveryBenchOptions::Validate() const {
  if (trials < 1) throw std::invalid_argument("bench delivery: --trials must be >= 1");
  if (mission != "deliver" && mission != "follow") {
    throw std::invalid_argument("bench delivery: --mission must be deliver or follow, not '" +
                                mission + "'");
  }
  for (const std::string& name : configurations) {
    if (name != kRelocalize && name != kOpenLoop) {
      throw std::invalid_argument("bench delivery: unknown configuration '" + name +
                                  "' (relocalize, open_loop)");
    }
  }
}

std::vector<std::string> DeliveryBenchOptions::ConfigurationNames() const {
  if (configurations.empty()) return {kRelocalize};
  std::vector<std::string> names;
  for (const char* name : {kRelocalize, kOpenLoop}) {
    if (std::find(configurations.begin(), configurations.end(), name) != configurations.end()) {
      names.push_back(name);
    }
  }
  return names;
}

std::vector<DeliveryFlight> FlyDeliveryField(const DeliveryBenchOptions& options, int trial) {
  std::vector<DeliveryFlight> flights;
  for (const std::string& configuration : options.ConfigurationNames()) {
    DeliveryFlight flight;
    flight.configuration = configuration;
    flight.seed = options.first_seed + static_cast<std::uint64_t>(trial);
    MissionFlightSpec spec;
    spec.scenario = "tags";
    spec.mission = options.mission;
    spec.set_items = options.set_items;
    if (configuration == kOpenLoop) spec.set_items.push_back("mission.robot_relocalize=false");
    spec.seed = flight.seed;
    try {
      flight.run = FlyMission(spec);
      flight.failure = FailureOf(flight.run);
    } catch (const std::invalid_argument& e) {
      // A field without a mission is the planner's failure (bench tags --section missions
      // counts those); anything else is a bench error.
      const std::string what = e.what();
      flight.failure = what.find("no mission") != std::string::npos ? "no_mission" : "error";
      flight.run.evaluation.outcome = what;
    }
    flights.push_back(flight);
  }
  return flights;
}

void WriteDeliverySections(const DeliveryBenchOptions& options,
                           const std::vector<DeliveryFlight>& flights, nlohmann::json* summary,
                           output::HtmlReport* report) {
  if (!options.flights_csv_path.empty()) WriteFlightsCsv(flights, options.flights_csv_path);
  nlohmann::json& s = *summary;
  s["delivery"]["mission"] = options.mission;
  for (const std::string& configuration : options.ConfigurationNames()) {
    s["delivery"][configuration] = ConfigurationRow(Of(flights, configuration));
  }
  nlohmann::json& acceptance = s["acceptance"];
  const nlohmann::json& relocalize = s["delivery"][kRelocalize];
  if (relocalize.is_object()) {
    acceptance["kit_on_goal_at_least_95_percent"] =
        relocalize["success_rate_percent"].get<double>() >= kSuccessTargetPercent;
  }

  report->AddSection("Missions: the first-aid kit on the goal, no collision, robot in view");
  report->AddTable(s["delivery"]);
  output::SvgPlot plot({"Servo: the robot's tag from the image centre, worst per flight",
                        "scene seed", "max offset [% of the image width]"});
  for (const std::string& configuration : options.ConfigurationNames()) {
    std::vector<double> seeds, offsets;
    for (const DeliveryFlight* f : Of(flights, configuration)) {
      seeds.push_back(static_cast<double>(f->seed));
      offsets.push_back(100 * Figure(*f, "max_offset_of_width"));
    }
    plot.AddScatter(configuration, seeds, offsets);
  }
  report->AddSvg(plot.Render(), "The issue's bound: 10 % of the image width");
}

nlohmann::json DeliveryFlightToJson(const DeliveryFlight& flight) {
  return {{"configuration", flight.configuration},
          {"seed", flight.seed},
          {"failure", flight.failure},
          {"run", MissionFlightRunToJson(flight.run)}};
}

DeliveryFlight DeliveryFlightFromJson(const nlohmann::json& json) {
  try {
    DeliveryFlight flight;
    flight.configuration = json.at("configuration").get<std::string>();
    flight.seed = json.at("seed").get<std::uint64_t>();
    flight.failure = json.at("failure").get<std::string>();
    flight.run = MissionFlightRunFromJson(json.at("run"));
    return flight;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("delivery flight record: ") + e.what());
  }
}

}  // namespace aperture::experiments
