#pragma once
// `aperture sim gap`: the vision gap mission (planning/gap_mission/gap_mission.h, seed 000) as the
// autopilot of the SITL run, its overlay and its ground-truth outcome in summary.json.
//
// Mission parameters come from the `mission` section (--config, `--set mission.<key>=<value>`;
// GapMissionParams fields, planning/gap_mission/gap_mission_params_io.h), starting from what the
// scenario defines (the pattern sizes, the forward camera, the IMU noise:
// experiments/gap/gap_mission_factory.h).
//
// Outcome on ground truth (never shown to the mission): the first crossing of the true gap plane
// (the scene's "gap" object, z_G from the approach side to the far side), whether B's origin was
// inside the opening then, and `passed` = crossed inside the opening without a collision. The
// error at the gap (seed 000 Table I: actual minus desired state when the gap plane is crossed)
// compares the ground truth at the crossing with the traverse plan at its t_c, the plan mapped
// from the mission frame to W through the true gap (T_WG_true * T_WG_est^-1), world axes.
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "planning/gap_mission/gap_mission.h"
#include "sim/scenario/scenario.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::apps {

class SimGapMission {
 public:
  // Mission parameters: what the scenario defines (GapMissionParamsFor), then the keys of
  // `mission_config` (the `mission` section). Throws std::invalid_argument naming the file or
  // --set item of a bad mission parameter.
  SimGapMission(const sim::Scenario& scenario, const sim::SitlRunnerParams& params,
                config::ParamReader& mission_config);

  // The effective mission parameters (every field; config::DumpParams writes them).
  const planning::GapMissionParams& params() const { return params_; }
  planning::GapMission& mission() { return *mission_; }
  // The latest detection's 16 corner segments and the phase, drawn onto the onboard image.
  void DrawOverlay(cv::Mat* onboard_bgr) const;
  // summary["mission"]: phases and their start times, detection and replanning counts, the
  // traverse plan, the ground-truth outcome and the error at the gap.
  nlohmann::json Summary(const sim::SitlResult& result, const sim::Scenario& scenario) const;
  // One line for the terminal.
  std::string OutcomeLine(const nlohmann::json& summary) const;

 private:
  planning::GapMissionParams params_;
  std::unique_ptr<planning::GapMission> mission_;
};

}  // namespace aperture::apps
