// A short closed-loop SITL flight of the forest mission on the path `aperture sim forest` takes
// (mission registry -> ForestMission on rendered colour frames + IMU + simulated odometry ->
// EvaluateForestFlight on ground truth): a trunk stands on the straight line to a goal 6 m away,
// so the flight only succeeds if the depth map, the waypoint selection and the spline steer
// around it. The whole forest (40 seeded layouts, 22 m) is `aperture bench mononav`'s.
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

TEST(ForestFlightSitl, FliesAroundATrunkOnTheLineToTheGoal) {
  // No random trees: one 0.3 m trunk 3 m ahead on the line, a box off to the side for texture.
  const std::vector<std::string> set_items = {"forest.trees=0",
                                              "forest.boxes=0",
                                              "forest.goal_m=[6.0, 0.0, 1.5]",
                                              "objects.trunk.shape=cylinder",
                                              "objects.trunk.radius_m=0.3",
                                              "objects.trunk.height_m=6",
                                              "objects.trunk.pose.p_m=[3.0, 0.0, 0.0]",
                                              "objects.trunk.texture.kind=bark"};
  const sim::ScenarioParams scenario_params =
      sim::LoadScenarioParams(sim::ScenarioConfig("forest", {}, set_items));
  sim::Scenario scenario = sim::BuildScenario(scenario_params);
  sim::SitlRunnerParams params;
  params.duration_s = 20.0;  // the seed-1 forest flight averaged 0.7 m/s: 6 m in ~9 s
  sim::ConfigureSitlFromScenario(scenario, &params);
  for (sim::SitlCamera& camera : params.cameras) camera.render.ground_truth = false;
  params.SetSeed(scenario_params.seed);

  MissionRegistry missions;
  RegisterBuiltinMissions(missions);
  ASSERT_EQ(missions.DefaultFor("forest"), "forest");
  const config::ConfigTree no_overrides = config::ConfigTree::FromCommandLine("", {}, {});
  config::ParamReader root = no_overrides.Reader();
  config::ParamReader mission_params = root.Section("mission");
  std::unique_ptr<MissionFlight> flight =
      missions.Create("forest", {scenario, params, mission_params});
  sim::SitlRunner runner(params, &scenario.scene());
  const sim::SitlResult result = runner.Run(flight->autopilot(), sim::MakeScenarioHooks(&scenario));
  const MissionEvaluation evaluation = flight->Evaluate(result);
  std::printf("  %s\n  wall %.1f s\n", evaluation.outcome.c_str(), result.timing.wall_time_s);

  EXPECT_TRUE(evaluation.passed) << evaluation.figures.dump(2);
  EXPECT_EQ(result.outcome, sim::SitlResult::Outcome::kAutopilotDone) << result.autopilot_status;
  // It went around the trunk: the straight line would have met it (clearance 0), the vehicle's
  // rotor tips reach 0.24 m from the centre.
  EXPECT_GT(evaluation.figures["min_clearance_m"].get<double>(), 0.24);
  EXPECT_EQ(evaluation.figures["nearest_obstacle"], "trunk");
  EXPECT_GT(evaluation.figures["frames"].get<int>(), 0);
}

}  // namespace
}  // namespace aperture::experiments
