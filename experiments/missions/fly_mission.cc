#include "experiments/missions/fly_mission.h"

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "config/config_tree.h"
#include "experiments/missions/builtin_missions.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_params.h"
#include "sim/scenario/scenario_sitl.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

namespace {

// A flight set up and not flown: the scenario, the SITL parameters (faults injected) and the
// mission built on the nominal ones.
struct PreparedFlight {
  std::unique_ptr<sim::Scenario> scenario;
  // Behind pointers: a mission may keep references to what it was built from.
  std::unique_ptr<sim::SitlRunnerParams> sitl;
  std::unique_ptr<MissionFlight> flight;
};

PreparedFlight Prepare(const MissionFlightSpec& spec) {
  std::vector<std::string> set_items = spec.set_items;
  set_items.push_back("seed=" + std::to_string(spec.seed));
  const config::ConfigTree tree = sim::ScenarioConfig(spec.scenario, {}, set_items);
  config::ParamReader root = tree.Reader();
  sim::ScenarioParams scenario_params;
  LoadParams(root, &scenario_params);
  config::ParamReader mission_params = root.Section("mission");
  root.RejectUnknownKeys();
  PreparedFlight prepared;
  prepared.scenario = std::make_unique<sim::Scenario>(sim::BuildScenario(scenario_params));
  prepared.sitl = std::make_unique<sim::SitlRunnerParams>();
  sim::SitlRunnerParams& sitl = *prepared.sitl;
  sitl.duration_s = spec.duration_s;
  sitl.trajectory_decimation = spec.trajectory_decimation;
  sitl.record_window_s = spec.record_window_s;
  sitl.render_ignored_frames = spec.render_ignored_frames;
  sim::ConfigureSitlFromScenario(*prepared.scenario, &sitl);
  for (sim::SitlCamera& camera : sitl.cameras) camera.render.ground_truth = false;
  sitl.SetSeed(spec.seed);

  MissionRegistry missions;
  RegisterBuiltinMissions(missions);
  const std::string mission =
      spec.mission.empty() ? missions.DefaultFor(scenario_params.scenario) : spec.mission;
  prepared.flight = missions.Create(mission, {*prepared.scenario, sitl, mission_params});
  sitl.duration_s = std::max(sitl.duration_s, prepared.flight->MinimumDurationS());
  if (spec.inject_faults) spec.inject_faults(&sitl);
  sitl.Validate();
  return prepared;
}

}  // namespace

void CheckMissionFlight(const MissionFlightSpec& spec) { Prepare(spec); }

MissionFlightRun FlyMission(const MissionFlightSpec& spec) {
  PreparedFlight prepared = Prepare(spec);
  MissionFlight* flight = prepared.flight.get();
  sim::SitlRunner runner(*prepared.sitl, &prepared.scenario->scene());
  sim::SitlHooks hooks = MakeMissionHooks(flight, prepared.scenario.get());
  if (spec.on_frame) {
    hooks.on_frame = [&spec](int camera_index, const sim::CapturedFrame&,
                             const control::QuadState& state) {
      spec.on_frame(camera_index, state.t_s);
    };
  }
  hooks.stop_requested = spec.stop_requested;
  const sim::SitlResult result = runner.Run(flight->autopilot(), hooks);
  if (spec.on_result) spec.on_result(result);
  MissionFlightRun run;
  run.evaluation = flight->Evaluate(result);
  run.sim_outcome = sim::ToString(result.outcome);
  run.sim_time_s = result.sim_time_s;
  run.wall_time_s = result.timing.wall_time_s;
  return run;
}

nlohmann::json MissionFlightRunToJson(const MissionFlightRun& run) {
  return {{"passed", run.evaluation.passed},   {"evaluation_outcome", run.evaluation.outcome},
          {"figures", run.evaluation.figures}, {"sim_outcome", run.sim_outcome},
          {"sim_time_s", run.sim_time_s},      {"wall_time_s", run.wall_time_s}};
}

MissionFlightRun MissionFlightRunFromJson(const nlohmann::json& json) {
  try {
    MissionFlightRun run;
    run.evaluation.passed = json.at("passed").get<bool>();
    run.evaluation.outcome = json.at("evaluation_outcome").get<std::string>();
    run.evaluation.figures = json.at("figures");
    run.sim_outcome = json.at("sim_outcome").get<std::string>();
    run.sim_time_s = json.at("sim_time_s").get<double>();
    run.wall_time_s = json.at("wall_time_s").get<double>();
    return run;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("mission flight record: ") + e.what());
  }
}

}  // namespace aperture::experiments
