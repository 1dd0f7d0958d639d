// Closed-loop SITL flight of the GapFlyt mission through the rendered `gapflyt` scenario on the
// path `aperture sim gapflyt` takes: the mission registry builds the flight (forward camera +
// simulated IMU + range sensor in, commands out; scan, TS²P, label tracking, servo, go through)
// and its ground-truth evaluator judges it: crossed inside the opening without a collision, with
// the footprint clear of the edge, and the detection the servo started from overlapping the true
// opening by >= 75 % (seed 002's success).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "config/config_tree.h"
#include "experiments/faults/fault_injection.h"
#include "experiments/missions/builtin_missions.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_sitl.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {
namespace {

struct GapflytCase {
  std::string shape;
  std::string law;
};

void PrintTo(const GapflytCase& c, std::ostream* os) { *os << c.shape << ", " << c.law; }

struct GapflytRun {
  sim::SitlResult result;
  MissionEvaluation evaluation;
};

// 320 x 240 images (a quarter of the scenario's pixels) keep a flight to a few CPU seconds; the
// TS²P and tracker radii scale with the image width.
// `fault`: one of `aperture sim --fault`'s, "NAME=LEVEL" (experiments/faults/fault_injection.h),
// drawn from `fault_seed` as `aperture sim --fault-seed`.
// `mission_items`: further `--set mission.*` items.
GapflytRun Fly(const std::vector<std::string>& scene_items, const std::string& law,
               double duration_s, const std::string& fault = "", std::uint64_t fault_seed = 0,
               const std::vector<std::string>& mission_items = {}) {
  std::vector<std::string> set_items = {"cameras.front.width=320", "cameras.front.height=240"};
  set_items.insert(set_items.end(), scene_items.begin(), scene_items.end());
  const sim::ScenarioParams scenario_params =
      sim::LoadScenarioParams(sim::ScenarioConfig("gapflyt", {}, set_items));
  sim::Scenario scenario = sim::BuildScenario(scenario_params);
  sim::SitlRunnerParams params;
  params.duration_s = duration_s;
  sim::ConfigureSitlFromScenario(scenario, &params);
  for (sim::SitlCamera& camera : params.cameras) camera.render.ground_truth = false;
  params.SetSeed(scenario_params.seed);
  if (!fault.empty()) {
    const FaultSetting setting = ParseFaultSetting(fault);
    InjectFault(setting.fault->kind, setting.level, DrawFault(fault_seed), &params);
  }

  MissionRegistry missions;
  RegisterBuiltinMissions(missions);
  EXPECT_EQ(missions.DefaultFor("gapflyt"), "gapflyt");
  std::vector<std::string> mission_set = {"mission.servo.law=" + law};
  mission_set.insert(mission_set.end(), mission_items.begin(), mission_items.end());
  const config::ConfigTree overrides = config::ConfigTree::FromCommandLine("", {}, mission_set);
  config::ParamReader root = overrides.Reader();
  config::ParamReader mission_params = root.Section("mission");
  std::unique_ptr<MissionFlight> flight =
      missions.Create("gapflyt", {scenario, params, mission_params});
  sim::SitlRunner runner(params, &scenario.scene());
  GapflytRun run;
  run.result = runner.Run(flight->autopilot(), sim::MakeScenarioHooks(&scenario));
  run.evaluation = flight->Evaluate(run.result);
  return run;
}

class GapflytMissionSitlTest : public ::testing::TestWithParam<GapflytCase> {};

TEST_P(GapflytMissionSitlTest, FliesThroughTheOpeningWithoutCollision) {
  const GapflytCase& c = GetParam();
  const GapflytRun run = Fly({"gapflyt.shape=" + c.shape, "seed=3"}, c.law, 12.0);
  const nlohmann::json& f = run.evaluation.figures;
  SCOPED_TRACE(f.dump(1));
  EXPECT_EQ(f["law"], c.law);
  ASSERT_TRUE(run.evaluation.passed) << run.evaluation.outcome;
  EXPECT_EQ(run.result.outcome, sim::SitlResult::Outcome::kAutopilotDone) << run.result.reason;
  EXPECT_EQ(f["phase"], "done");
  EXPECT_TRUE(f["detection"]["detected"].get<bool>());
  // The footprint cleared the edge (the evaluator's clearance > 0 means no part overlapped the
  // wall's plane outline).
  EXPECT_GT(f["clearance_m"].get<double>(), 0.0);
  // The servo aimed at the opening: within a third of its half-height (0.4 m) of the centroid.
  EXPECT_LT(f["crossing_offset_norm_m"].get<double>(), 0.4 / 3.0 * 2.0);
}

// `aperture bench gapflyt --seed 2`, trial 41: the first scan's TS²P opening leaked into ~30 % of
// the wall up to the image border, and the mission committed at once from 2.5 m (the border test
// of a view filling up) and stopped short of the wall. A detection reaching the border from the
// scan is refused; the scan back finds the opening.
TEST(GapflytRescanSitlTest, RescansWhenTheDetectionRunsIntoTheBorder) {
  const GapflytRun run =
      Fly({"seed=14093126369638373958", "gapflyt.shape=polygon", "gapflyt.size_m=[0.8591, 0.8297]",
           "gapflyt.center_m=[-0.1545, 1.3545]", "gapflyt.foreground_x_m=2.5169",
           "gapflyt.background_x_m=6.0322"},
          "moments", 12.0);
  const nlohmann::json& f = run.evaluation.figures;
  SCOPED_TRACE(f.dump(1));
  const std::vector<std::string> statuses = f["scan_statuses"].get<std::vector<std::string>>();
  ASSERT_GE(statuses.size(), 2u);
  EXPECT_NE(statuses.front().find("image border"), std::string::npos) << statuses.front();
  EXPECT_EQ(statuses.back(), "ok");
  EXPECT_TRUE(run.evaluation.passed) << run.evaluation.outcome;
}

// `aperture bench faults --mission gapflyt`: a rotor 15 % weak from the start crashed 20 of 20
// flights. Its torque transient tilted the vehicle 4.6 deg under the zero rates the mission
// commanded while the odometry calibrated "at rest"; the calibration took that for level and the
// vehicle accelerated into the wall. The calibration phase now holds the start attitude on the
// gyro (control/gyro_attitude_hold.h).
TEST(GapflytWeakMotorSitlTest, AWeakRotorFromTheStartDoesNotFoolTheCalibration) {
  const GapflytRun run =
      Fly({"gapflyt.shape=polygon", "seed=3"}, "moments", 12.0, "motor_loss=0.15");
  EXPECT_FALSE(run.result.collision) << run.result.reason;
  EXPECT_TRUE(run.evaluation.passed) << run.evaluation.outcome;
}

INSTANTIATE_TEST_SUITE_P(Shapes, GapflytMissionSitlTest,
                         ::testing::Values(GapflytCase{"polygon", "moments"},
                                           GapflytCase{"ellipse", "pid"}));

// `aperture bench faults --mission gapflyt`: a 2.5 m/s gust pushed the vehicle 1.4 m aside in
// the servo phase; on its way back the opening reached the image border 0.8 m off the vehicle's
// line, and the commit there flew the blind line into the wall (the drag-aided odometry, which
// measures airspeed, had also run past the wall's distance). A border commit now waits until the
// aimed line is within commit_max_aim_offset_m. At the scenario's 640 x 480: at 320 x 240 this
// flight commits by the moment servo's convergence instead.
TEST(GapflytGustSitlTest, ABorderCommitWaitsUntilTheAimedLineIsWithinReach) {
  const GapflytRun run = Fly(
      {"cameras.front.width=640", "cameras.front.height=480", "seed=5211480184160126311"},
      "moments", 15.0, "gust=2.5", 8923224485621549272ull);
  const nlohmann::json& f = run.evaluation.figures;
  SCOPED_TRACE(f.dump(1));
  EXPECT_FALSE(run.result.collision) << run.result.reason;
  EXPECT_TRUE(run.evaluation.passed) << run.evaluation.outcome;
  ASSERT_TRUE(f.contains("commit_aim_offset_m"));
  EXPECT_LE(f["commit_aim_offset_m"].get<double>(), 0.35);
}

// A servo that does not converge within mission.max_servo_s (x10 IMU noise held the moment
// error above the commit threshold for 12 s in `aperture bench faults`, and the commit came as
// the flight's time ran out) no longer commits: it holds on the servo, in front of the opening.
// Here the bound is cut to 1 s, below the servo's 2-5 s: the vehicle must end hovering short of
// the wall, still tracking the opening.
TEST(GapflytServoTimeoutSitlTest, AServoThatDoesNotConvergeHoldsInsteadOfCommitting) {
  const GapflytRun run = Fly({"gapflyt.shape=polygon", "seed=3"}, "moments", 9.0, "", 0,
                             {"mission.max_servo_s=1.0"});
  const nlohmann::json& f = run.evaluation.figures;
  SCOPED_TRACE(f.dump(1));
  EXPECT_FALSE(run.result.collision) << run.result.reason;
  EXPECT_FALSE(run.evaluation.passed);
  EXPECT_EQ(f["phase"], "servo");
  EXPECT_EQ(f["reason"], "servo did not converge in 1.0 s");
  EXPECT_NE(f["status"].get<std::string>().find("holding"), std::string::npos);
  ASSERT_FALSE(run.result.trajectory.empty());
  EXPECT_LT(run.result.trajectory.back().v_W.norm(), 0.2);  // holding, not flying at the wall
}

// `aperture bench faults --mission gapflyt`, 5 m/s gusts (twice the default level). A gust pushed
// the vehicle aside in the servo phase; it swung back through the goal view at 0.3-0.4 m/s
// sideways, the moment error passed below commit_error on the way, and the blind line carried
// that motion into the wall. A converged commit now also needs the error to have been still
// (commit_max_error_rate over commit_rate_window_s); the flight commits 0.7 s later and passes.
TEST(GapflytGustSitlTest, AConvergedServoCommitsOnlyOnceTheImageIsStill) {
  const GapflytRun run = Fly({"seed=8418766560916313300"}, "moments", 15.0, "gust=5",
                             15695586125158153577ull);
  const nlohmann::json& f = run.evaluation.figures;
  SCOPED_TRACE(f.dump(1));
  EXPECT_FALSE(run.result.collision) << run.result.reason;
  EXPECT_TRUE(run.evaluation.passed) << run.evaluation.outcome;
  EXPECT_EQ(f["reason"], "moment servo converged");
}

// Same sweep: the gust blew while the opening reached the image border, and the commit there
// flew the blind line with the gust still pushing it (0.25 m sideways into the edge). No commit
// while the odometry coasts through suspected wind (control/drag_aided_odometry.h): the servo
// holds the view until the gust has passed. At the scenario's 640 x 480 (at 320 x 240 the early
// commit happens to pass).
TEST(GapflytGustSitlTest, NoCommitWhileTheGustBlows) {
  const GapflytRun run =
      Fly({"cameras.front.width=640", "cameras.front.height=480", "seed=2856035749236636358"},
          "moments", 15.0, "gust=5", 7982195280946046268ull);
  const nlohmann::json& f = run.evaluation.figures;
  SCOPED_TRACE(f.dump(1));
  EXPECT_FALSE(run.result.collision) << run.result.reason;
  EXPECT_TRUE(run.evaluation.passed) << run.evaluation.outcome;
}

// The `mission` section is strict: unknown keys, invalid values and the wrong scenario are named.
TEST(GapflytMissionParamsTest, BadParametersAndScenariosAreNamed) {
  const auto create = [](const std::string& scenario_name, const std::string& item) {
    sim::Scenario scenario =
        sim::BuildScenario(sim::LoadScenarioParams(sim::ScenarioConfig(scenario_name)));
    sim::SitlRunnerParams params;
    sim::ConfigureSitlFromScenario(scenario, &params);
    MissionRegistry missions;
    RegisterBuiltinMissions(missions);
    const config::ConfigTree tree = config::ConfigTree::FromCommandLine("", {}, {item});
    config::ParamReader root = tree.Reader();
    config::ParamReader section = root.Section("mission");
    return missions.Create("gapflyt", {scenario, params, section});
  };
  EXPECT_EQ(create("gapflyt", "mission.servo.law=pid")->autopilot().name(), "gapflyt_mission");
  const auto expect_error = [&](const std::string& scenario, const std::string& item,
                                const std::string& named) {
    try {
      create(scenario, item);
      ADD_FAILURE() << item << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
    }
  };
  expect_error("gapflyt", "mission.scan_sped_mps=0.6", "scan_sped_mps");
  expect_error("gapflyt", "mission.scan_speed_mps=-1", "scan_speed_mps");
  expect_error("gapflyt", "mission.servo.law=visual", "visual");
  expect_error("gapflyt", "mission.scan_cruise_s=0.1", "scan_cruise_s");  // < the ts2p window
  expect_error("gapflyt", "mission.odometry.wind_gate_mps=0", "wind_gate_mps");
  expect_error("gapflyt", "mission.commit_max_aim_offset_m=-0.1", "commit_max_aim_offset_m");
  expect_error("gapflyt", "mission.max_servo_s=0", "max_servo_s");
  expect_error("gapflyt", "mission.odometry.max_correction_noise=-1", "max_correction_noise");
  expect_error("gap", "mission.settle_s=1", "gapflyt scenario");
}

}  // namespace
}  // namespace aperture::experiments
