// Closed-loop SITL flights of the vision gap mission through the rendered `gap` scenario, on the
// path `aperture sim gap` takes: the mission registry builds the flight (180 deg fisheye images +
// simulated IMU in, commands out) and its one ground-truth evaluator (gap_trial_evaluation.h, the
// one `aperture bench gap` uses) judges it: crossed inside the opening, no collision, hovering
// behind the gap at the end, and the error at the gap (Table I analog).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "config/config_tree.h"
#include "experiments/missions/builtin_missions.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_sitl.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {
namespace {

struct GapCase {
  double roll_deg = 0.0;
  double pitch_deg = 0.0;
  int supersampling = 2;
};

void PrintTo(const GapCase& c, std::ostream* os) {
  *os << "roll " << c.roll_deg << " deg, pitch " << c.pitch_deg << " deg, supersampling "
      << c.supersampling;
}

class GapMissionSitlTest : public ::testing::TestWithParam<GapCase> {};

// 30 Hz camera (the demo's rate) to keep each flight near a minute of wall time on a loaded
// 2-core machine; seeded, so every run flies the same. 14 s: the mission crosses at ~9-10 s, and
// the recovery needs ~1-2 s to reach its position stage plus recovered_hold_s (2 s) there.
TEST_P(GapMissionSitlTest, CrossesInsideTheOpeningAndRecoversToAHover) {
  const GapCase& c = GetParam();
  const std::vector<std::string> set_items = {
      "gap.roll_deg=" + std::to_string(c.roll_deg), "gap.pitch_deg=" + std::to_string(c.pitch_deg),
      "cameras.front.rate_hz=30", "cameras.front.supersampling=" + std::to_string(c.supersampling)};
  const sim::ScenarioParams scenario_params =
      sim::LoadScenarioParams(sim::ScenarioConfig("gap", {}, set_items));
  sim::Scenario scenario = sim::BuildScenario(scenario_params);
  sim::SitlRunnerParams params;
  params.duration_s = 14.0;
  params.trajectory_decimation = 1;
  sim::ConfigureSitlFromScenario(scenario, &params);
  for (sim::SitlCamera& camera : params.cameras) camera.render.ground_truth = false;
  params.SetSeed(scenario_params.seed);

  MissionRegistry missions;
  RegisterBuiltinMissions(missions);
  const config::ConfigTree no_overrides = config::ConfigTree::FromCommandLine("", {}, {});
  config::ParamReader root = no_overrides.Reader();
  config::ParamReader mission_params = root.Section("mission");
  std::unique_ptr<MissionFlight> flight =
      missions.Create(missions.DefaultFor("gap"), {scenario, params, mission_params});
  sim::SitlRunner runner(params, &scenario.scene());
  const sim::SitlResult result = runner.Run(flight->autopilot(), sim::MakeScenarioHooks(&scenario));
  const MissionEvaluation evaluation = flight->Evaluate(result);
  std::printf("  %s\n  wall %.1f s\n", evaluation.outcome.c_str(), result.timing.wall_time_s);

  EXPECT_TRUE(evaluation.passed) << evaluation.figures.dump(2);
  EXPECT_EQ(result.outcome, sim::SitlResult::Outcome::kAutopilotDone) << result.autopilot_status;
  ASSERT_TRUE(evaluation.figures.contains("error_at_gap")) << evaluation.figures.dump(2);
  // Table I (seed 000): 4 / 4 / 3 cm mean position error over real flights; a single seeded flight
  // of ours stays within that on every axis (README: ~0.4 / 0.8 / 1.5 cm means over 100 trials).
  const nlohmann::json& position = evaluation.figures["error_at_gap"]["position_m"];
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_LT(std::abs(position[axis].get<double>()), 0.04) << "axis " << axis;
  }
}

// A level gap and one rolled and pitched (the demo test flies the 30 deg roll of `make demo`).
INSTANTIATE_TEST_SUITE_P(Inclinations, GapMissionSitlTest,
                         ::testing::Values(GapCase{0.0, 0.0, 2}, GapCase{25.0, 20.0, 2}));

}  // namespace
}  // namespace aperture::experiments
