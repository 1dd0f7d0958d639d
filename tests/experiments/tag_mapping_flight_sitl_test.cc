// A short closed-loop SITL flight of the tag mapping mission on the path `aperture sim tags`
// takes (mission registry -> TagMappingAutopilot on rendered downward frames + IMU + simulated
// odometry -> EvaluateTagMap on ground truth), over a small field (1.5 x 2 m, the origin tag, the
// goal mat and the robot) at a quarter of the camera's pixels and low (the smallest tag at 30 px)
// so that it runs in seconds with two tracks: the flight has to finish its tracks, map every tag
// and keep the map within the 2 cm. The full 4 x 6 m field is `aperture sim tags`
// (docs/results/tags.md).
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

TEST(TagMappingFlightSitl, MapsASmallFieldWithinTwoCentimetres) {
  const std::vector<std::string> set_items = {
      "tags.area_m=[1.5, 2.0]",   "tags.goal_xy_m=[1.1, 1.6]",          "tags.fixed_obstacles=0",
      "tags.movable_obstacles=0", "vehicle.start.p_m=[0.75, 1.0, 2.0]", "cameras.down.width=320",
      "cameras.down.height=240"};
  const sim::ScenarioParams scenario_params =
      sim::LoadScenarioParams(sim::ScenarioConfig("tags", {}, set_items));
  sim::Scenario scenario = sim::BuildScenario(scenario_params);
  sim::SitlRunnerParams params;
  params.duration_s = 30.0;
  sim::ConfigureSitlFromScenario(scenario, &params);
  for (sim::SitlCamera& camera : params.cameras) camera.render.ground_truth = false;
  params.SetSeed(scenario_params.seed);

  MissionRegistry missions;
  RegisterBuiltinMissions(missions);
  ASSERT_EQ(missions.DefaultFor("tags"), "deliver");  // whose first stage is this flight
  // 30 px for the 0.25 m tags: 1.33 m high, two tracks over the small field.
  const config::ConfigTree overrides =
      config::ConfigTree::FromCommandLine("", {}, {"mission.min_tag_side_px=30"});
  config::ParamReader root = overrides.Reader();
  config::ParamReader mission_params = root.Section("mission");
  std::unique_ptr<MissionFlight> flight =
      missions.Create("map", {scenario, params, mission_params});
  sim::SitlRunner runner(params, &scenario.scene());
  const sim::SitlResult result = runner.Run(flight->autopilot(), sim::MakeScenarioHooks(&scenario));
  const MissionEvaluation evaluation = flight->Evaluate(result);
  std::printf("  %s\n  wall %.1f s\n", evaluation.outcome.c_str(), result.timing.wall_time_s);

  EXPECT_TRUE(evaluation.passed) << evaluation.figures.dump(2);
  EXPECT_EQ(result.outcome, sim::SitlResult::Outcome::kAutopilotDone) << result.autopilot_status;
  // `aperture sim` without --duration flies MinimumDurationS: the plan (done here at its end, the
  // first estimate at the first odometry pose) and a 5 s margin.
  EXPECT_NEAR(result.sim_time_s, flight->MinimumDurationS() - 5.0, 0.1);
  const nlohmann::json& f = evaluation.figures;
  EXPECT_EQ(f["tags_mapped"], 3);
  EXPECT_EQ(f["tags_total"], 3);
  EXPECT_EQ(f["flipped_tags"], 0);
  EXPECT_LE(f["map_rms_after_m"].get<double>(), 0.02);
  // The height rule on the 160 px camera (f = 160 px): the ground's 0.25 m tags bind.
  EXPECT_NEAR(f["height_m"].get<double>(), 160.0 * 0.25 / 30.0, 1e-6);
  EXPECT_EQ(f["tracks"], 2);
}

}  // namespace
}  // namespace aperture::experiments
