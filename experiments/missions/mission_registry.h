#pragma once
// Missions by name, the way front ends are (perception/graph/front_end_registry.h): each brings
// its factory (an autopilot from what the vehicle knows of a scenario plus the `mission`
// configuration section), its ground-truth evaluator and its report sections. `aperture sim
// NAME`, `aperture bench` and the tests all fly and score a mission through this one path.
//
//   MissionRegistry missions;
//   RegisterBuiltinMissions(missions);             // experiments/missions/builtin_missions.h
//   std::unique_ptr<MissionFlight> flight = missions.Create(name, {scenario, sitl_params, reader});
//   SitlResult result = SitlRunner(sitl_params, &scenario.scene()).Run(flight->autopilot(), hooks);
//   MissionEvaluation evaluation = flight->Evaluate(result);  // ground truth, after the run
//
// Autopilots themselves live in planning/ (flown from sensors only) or, for ground-truth
// references, in sim/; a MissionFlight only builds one and scores its flight.
#include <yaml-cpp/yaml.h>

#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "output/html_report.h"
#include "perception/autopilot.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_sitl.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

// What a mission's factory is given. The autopilot may only use what a real vehicle knows: the
// cameras and their mounts (scenario.cameras()), the sizes of what it is told to fly to
// (scenario.params()), the vehicle model and the IMU specification (sitl); the scene's object
// poses are ground truth, for the evaluator only.
struct MissionContext {
  const sim::Scenario& scenario;
  const sim::SitlRunnerParams& sitl;
  // The `mission` section (`--set mission.<key>=...`); the registry rejects keys left unread.
  config::ParamReader& params;
};

// A mission's outcome on ground truth.
struct MissionEvaluation {
  bool passed = false;
  std::string outcome;     // one line for the terminal, e.g. "passed the gap, error [...] m"
  nlohmann::json figures;  // summary.json "mission" (with "passed" added by the caller)
};

// One flight of a mission: the autopilot to fly and what scores it afterwards.
class MissionFlight {
 public:
  virtual ~MissionFlight() = default;
  // The autopilot the SITL flies; lives as long as this object.
  virtual perception::Autopilot& autopilot() = 0;
  // The mission's effective parameters, every field (config::DumpParams of its parameter struct):
  // the `mission` section of summary.json "config", which `--config summary.json` reads back.
  virtual YAML::Node EffectiveParams() const { return YAML::Node(YAML::NodeType::Map); }
  // The simulated time the mission needs to finish [s] (0: none); `aperture sim` flies at least
  // this long unless --duration says otherwise.
  virtual double MinimumDurationS() const { return 0.0; }
  // Moves the scene objects the mission scripts (the ground robot executing its mission) to their
  // poses at t_s; called before every camera frame is rendered (MakeMissionHooks).
  virtual void MoveObjects(double /*t_s*/, sim::Scene* /*scene*/) {}
  // Draws the mission's perception on the onboard camera image of the latest frame (the video).
  virtual void DrawOverlay(cv::Mat& /*onboard_bgr*/) const {}
  // Scores the finished run on ground truth (once, after the run).
  virtual MissionEvaluation Evaluate(const sim::SitlResult& result) = 0;
  // Writes the mission's own files into `directory` (after Evaluate); returns summary.json
  // "outputs" entries (key -> file name).
  virtual std::map<std::string, std::string> WriteFiles(const std::string& /*directory*/) const {
    return {};
  }
  // Sections for report.html after the summary (plots of the mission's own figures).
  virtual void AddReportSections(const MissionEvaluation& /*evaluation*/,
                                 const sim::SitlResult& /*result*/,
                                 output::HtmlReport* /*report*/) const {}
};

// The SITL hooks of a mission flight: the scenario's (body-attached objects follow the vehicle)
// after the flight's MoveObjects. `flight` and `scenario` must outlive the run.
sim::SitlHooks MakeMissionHooks(MissionFlight* flight, sim::Scenario* scenario);

using MissionFactory = std::function<std::unique_ptr<MissionFlight>(const MissionContext& context)>;

class MissionRegistry {
 public:
  // `scenarios`: the scenarios this mission is the default of (`aperture sim SCENARIO`). Throws
  // std::invalid_argument on an empty or repeated name, an empty factory, or a scenario that
  // already has a default mission.
  void Register(const std::string& name, std::string description,
                std::vector<std::string> scenarios, MissionFactory factory);

  bool Contains(const std::string& name) const { return entries_.count(name) > 0; }
  std::vector<std::string> Names() const;  // sorted
  const std::string& Description(const std::string& name) const;
  // The mission `aperture sim SCENARIO` flies; throws std::invalid_argument naming the scenario
  // and the missions when none is registered for it.
  const std::string& DefaultFor(const std::string& scenario) const;

  // Throws std::invalid_argument for an unknown name (listing the known ones), passes on the
  // factory's errors, and rejects `mission` keys the factory did not read.
  std::unique_ptr<MissionFlight> Create(const std::string& name,
                                        const MissionContext& context) const;

 private:
  struct Entry {
    std::string description;
    MissionFactory factory;
  };
  const Entry& Find(const std::string& name) const;

  std::map<std::string, Entry> entries_;
  std::map<std::string, std::string> default_for_scenario_;
};

}  // namespace aperture::experiments
