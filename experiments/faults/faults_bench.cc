#include "experiments/faults/faults_bench.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <set>
#include <stdexcept>

#include "experiments/missions/fly_mission.h"
#include "sim/scene/counter_hash.h"

namespace aperture::experiments {
namespace {

// The paper's range of gap inclinations (seed 000 Sec. IV-B), as `aperture bench gap` draws them.
constexpr double kGapMaxRollDeg = 45.0;
constexpr double kGapMaxPitchDeg = 30.0;

std::string NumberItem(const std::string& key, double value) {
  char item[80];
  std::snprintf(item, sizeof(item), "%s=%.3f", key.c_str(), value);
  return item;
}

// The condition of repeat r besides its seed: the gap's inclination for `gap`, nothing else.
std::vector<std::string> ConditionItems(const std::string& scenario, std::uint64_t seed) {
  if (scenario != "gap") return {};
  return {NumberItem("gap.roll_deg",
                     kGapMaxRollDeg * sim::UniformFromHash(sim::HashCounters(seed, 11))),
          NumberItem("gap.pitch_deg",
                     kGapMaxPitchDeg * sim::UniformFromHash(sim::HashCounters(seed, 12)))};
}

}  // namespace

void FaultsBenchOptions::Validate() const {
  if (scenario.empty()) throw std::invalid_argument("--mission: name a scenario, e.g. gap or led");
  if (repeats < 1) {
    throw std::invalid_argument("--trials " + std::to_string(repeats) + ": must be >= 1");
  }
  if (!(std::isfinite(duration_s) && duration_s > 0.0)) {
    throw std::invalid_argument("--duration " + std::to_string(duration_s) + ": must be > 0 s");
  }
  std::set<std::string> seen;
  for (const std::string& name : faults) {
    FindFault(name);  // throws for an unknown name, listing the faults
    if (!seen.insert(name).second) {
      throw std::invalid_argument("--faults: '" + name + "' is listed twice");
    }
  }
}

std::vector<FaultSpec> FaultsBenchOptions::SelectedFaults() const {
  std::vector<FaultSpec> selected;
  for (const FaultSpec& fault : FaultCatalogue()) {
    bool wanted = faults.empty();
    for (const std::string& name : faults) wanted |= name == fault.name;
    if (wanted) selected.push_back(fault);
  }
  return selected;
}

std::vector<double> FaultsBenchOptions::LevelsAboveNone(const FaultSpec& fault) const {
  if (acceptance_levels) return {fault.DefaultLevel(), fault.TwiceDefaultLevel()};
  std::vector<double> levels = fault.SweepLevels();
  levels.erase(levels.begin());  // level 0 is the baseline
  return levels;
}

int FaultsBenchOptions::TrialsPerRepeat() const {
  int per_repeat = 1;
  for (const FaultSpec& fault : SelectedFaults()) {
    per_repeat += static_cast<int>(LevelsAboveNone(fault).size());
  }
  return per_repeat;
}

nlohmann::json FaultsBenchOptionsToJson(const FaultsBenchOptions& options) {
  return {{"scenario", options.scenario},  {"repeats", options.repeats},
          {"seed", options.seed},          {"duration_s", options.duration_s},
          {"faults", options.faults},      {"acceptance_levels", options.acceptance_levels},
          {"set_items", options.set_items}};
}

FaultsBenchOptions FaultsBenchOptionsFromJson(const nlohmann::json& json) {
  FaultsBenchOptions options;
  try {
    options.scenario = json.at("scenario").get<std::string>();
    options.repeats = json.at("repeats").get<int>();
    options.seed = json.at("seed").get<std::uint64_t>();
    options.duration_s = json.at("duration_s").get<double>();
    options.faults = json.at("faults").get<std::vector<std::string>>();
    options.acceptance_levels = json.at("acceptance_levels").get<bool>();
    options.set_items = json.at("set_items").get<std::vector<std::string>>();
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("bench faults options: ") + e.what());
  }
  options.Validate();
  return options;
}

FaultTrialPlan PlanFaultTrial(const FaultsBenchOptions& options, int trial) {
  if (trial < 0 || trial >= options.Trials()) {
    throw std::invalid_argument("bench faults: trial " + std::to_string(trial) + " outside [0, " +
                                std::to_string(options.Trials()) + ")");
  }
  FaultTrialPlan plan;
  const int per_repeat = options.TrialsPerRepeat();
  plan.repeat = trial / per_repeat;
  int slot = trial % per_repeat;
  // Seeds below 2^63: every command reads them exactly (the one seed rule).
  const std::uint64_t repeat_hash =
      sim::HashCounters(options.seed, static_cast<std::uint64_t>(plan.repeat));
  plan.seed = repeat_hash >> 1;
  plan.fault_seed = sim::MixBits(repeat_hash);
  plan.condition_items = ConditionItems(options.scenario, repeat_hash);
  if (slot == 0) return plan;
  --slot;
  for (const FaultSpec& fault : options.SelectedFaults()) {
    const std::vector<double> levels = options.LevelsAboveNone(fault);
    if (slot < static_cast<int>(levels.size())) {
      plan.fault = fault.name;
      plan.level = levels[static_cast<std::size_t>(slot)];
      return plan;
    }
    slot -= static_cast<int>(levels.size());
  }
  throw std::logic_error("bench faults: trial slot beyond the selected faults");
}

std::string ReplayCommand(const FaultsBenchOptions& options, const FaultTrialPlan& plan) {
  char duration[32];
  std::snprintf(duration, sizeof(duration), "%.12g", options.duration_s);
  std::string command = "aperture sim " + options.scenario + " --seed " +
                        std::to_string(plan.seed) + " --duration " + duration;
  if (plan.fault != "none") {
    char level[32];
    std::snprintf(level, sizeof(level), "%.12g", plan.level);
    command += " --fault " + plan.fault + "=" + level + " --fault-seed " +
               std::to_string(plan.fault_seed);
  }
  for (const std::string& item : plan.condition_items) command += " --set " + item;
  for (const std::string& item : options.set_items) command += " --set '" + item + "'";
  return command;
}

nlohmann::json FlyFaultTrial(const FaultsBenchOptions& options, int trial) {
  const FaultTrialPlan plan = PlanFaultTrial(options, trial);
  nlohmann::json record = {{"repeat", plan.repeat},
                           {"fault", plan.fault},
                           {"level", plan.level},
                           {"seed", plan.seed},
                           {"fault_seed", plan.fault_seed},
                           {"condition", plan.condition_items},
                           {"replay", ReplayCommand(options, plan)}};
  MissionFlightSpec spec;
  spec.scenario = options.scenario;
  spec.set_items = plan.condition_items;
  spec.set_items.insert(spec.set_items.end(), options.set_items.begin(), options.set_items.end());
  spec.seed = plan.seed;
  spec.duration_s = options.duration_s;
  spec.render_ignored_frames = false;
  if (plan.fault != "none") {
    const FaultKind kind = FindFault(plan.fault).kind;
    const FaultDraw draw = DrawFault(plan.fault_seed);
    spec.inject_faults = [kind, &plan, draw](sim::SitlRunnerParams* sitl) {
      InjectFault(kind, plan.level, draw, sitl);
    };
  }
  FlightOutcome outcome;
  spec.on_result = [&outcome](const sim::SitlResult& result) {
    outcome = ClassifyFlight(false, result);  // the mission's verdict comes after Evaluate
  };
  try {
    const MissionFlightRun run = FlyMission(spec);
    if (run.evaluation.passed) outcome = {FlightOutcomeKind::kSuccess, ""};
    record["outcome"] = ToString(outcome.kind);
    record["reason"] = outcome.reason;
    record["mission_passed"] = run.evaluation.passed;
    record["mission_outcome"] = run.evaluation.outcome;
    record["sim_outcome"] = run.sim_outcome;
    record["sim_time_s"] = run.sim_time_s;
    record["wall_time_s"] = run.wall_time_s;
  } catch (const std::exception& e) {
    record["outcome"] = "error";
    record["reason"] = std::string("error: ") + e.what();
    record["mission_passed"] = false;
    record["mission_outcome"] = "";
    record["sim_outcome"] = "error";
    record["sim_time_s"] = 0.0;
    record["wall_time_s"] = 0.0;
  }
  return record;
}

}  // namespace aperture::experiments
