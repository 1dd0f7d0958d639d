#pragma once
// One seeded closed-loop SITL flight of a registered mission in a built-in scenario, for benches
// that count missions over many scenes: the scenario from its name and `--set`-style items
// (scenario keys and mission.*), the mission from the builtin registry, the run through
// MakeMissionHooks (objects the mission moves), scored by the mission's own Evaluate. No video,
// no per-frame outputs.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/missions/mission_registry.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

struct MissionFlightRun {
  MissionEvaluation evaluation;
  std::string sim_outcome;  // sim::ToString(SitlResult::Outcome)
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
};

struct MissionFlightSpec {
  std::string scenario;
  std::string mission;  // empty = the scenario's default mission
  std::vector<std::string> set_items;
  std::uint64_t seed = 0;  // the scenario's (layout) and the sensors' noise
  // Simulated time; the mission's MinimumDurationS when longer (it may end earlier) [s].
  double duration_s = 0.0;
  int trajectory_decimation = 5;  // ground truth kept every k-th 1 kHz state
  // false: frames the mission says it would ignore are not rendered (the same flight, fewer
  // renders; sim::SitlRunnerParams::render_ignored_frames).
  bool render_ignored_frames = true;
  // > 0: the flight keeps only its last record_window_s of records and is scored on them
  // (sim::SitlRunnerParams::record_window_s: flat memory over a long flight) [s].
  double record_window_s = 0.0;
  // Optional observers of the flight (aperture bench soak's samples): every rendered camera
  // frame's camera index and simulated time; asked before every simulation step whether to stop
  // (sim::SitlHooks::stop_requested); the raw SITL result before it is scored.
  std::function<void(int camera_index, double t_s)> on_frame;
  std::function<bool()> stop_requested;
  std::function<void(const sim::SitlResult&)> on_result;
  // Changes the SITL parameters after the mission was built on the nominal ones, before the run
  // (faults the mission is not told of: aperture bench faults).
  std::function<void(sim::SitlRunnerParams*)> inject_faults;
};

// Throws std::invalid_argument (or config::UsageError) for an unknown scenario, mission or key,
// or a mission that cannot be set up on the scene.
MissionFlightRun FlyMission(const MissionFlightSpec& spec);
// Sets the flight up as FlyMission does (scenario, mission, injected faults) without flying it:
// the same exceptions, so a bench rejects a bad key before its first flight.
void CheckMissionFlight(const MissionFlightSpec& spec);

// A run as JSON and back, exactly (trial records of Monte-Carlo benches); std::invalid_argument
// naming a missing or malformed key.
nlohmann::json MissionFlightRunToJson(const MissionFlightRun& run);
MissionFlightRun MissionFlightRunFromJson(const nlohmann::json& json);

}  // namespace aperture::experiments
