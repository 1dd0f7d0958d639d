// The mission registry: names, defaults per scenario, strict `mission` parameters, and the
// built-in missions building their autopilots from a scenario.
#include "experiments/missions/mission_registry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>

#include "config/config_tree.h"
#include "experiments/missions/builtin_missions.h"
#include "sim/scenario/scenario_sitl.h"

namespace aperture::experiments {
namespace {

using ::testing::HasSubstr;

class NullFlight final : public MissionFlight {
 public:
  perception::Autopilot& autopilot() override { throw std::logic_error("not flown"); }
  MissionEvaluation Evaluate(const sim::SitlResult& /*result*/) override { return {}; }
};

std::unique_ptr<MissionFlight> MakeNull(const MissionContext& context) {
  double gain = 1.0;
  context.params.Read("gain", &gain);
  return std::make_unique<NullFlight>();
}

TEST(MissionRegistryTest, NamesDefaultsAndDuplicates) {
  MissionRegistry registry;
  registry.Register("a", "first", {"gap"}, MakeNull);
  registry.Register("b", "second", {}, MakeNull);
  EXPECT_EQ(registry.Names(), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(registry.DefaultFor("gap"), "a");
  try {
    registry.DefaultFor("forest");
    FAIL() << "a scenario without a default mission was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("'forest'"));
    EXPECT_THAT(e.what(), HasSubstr("a b"));
  }
  EXPECT_THROW(registry.Register("a", "again", {}, MakeNull), std::invalid_argument);
  EXPECT_THROW(registry.Register("c", "same scenario", {"gap"}, MakeNull), std::invalid_argument);
  EXPECT_THROW(registry.Register("d", "no factory", {}, nullptr), std::invalid_argument);
}

class BuiltinMissionsTest : public ::testing::Test {
 protected:
  BuiltinMissionsTest() { RegisterBuiltinMissions(registry_); }

  // The scenario with tiny cameras (construction only, nothing is rendered here).
  void Load(const std::string& scenario_name) {
    scenario_ = std::make_unique<sim::Scenario>(
        sim::BuildScenario(sim::LoadScenarioParams(sim::ScenarioConfig(scenario_name, {}, {}))));
    sim::ConfigureSitlFromScenario(*scenario_, &sitl_);
  }

  std::unique_ptr<MissionFlight> Create(const std::string& mission,
                                        const std::vector<std::string>& set_items) {
    const config::ConfigTree tree = config::ConfigTree::FromCommandLine("", {}, set_items);
    config::ParamReader root = tree.Reader();
    config::ParamReader section = root.Section("mission");
    return registry_.Create(mission, {*scenario_, sitl_, section});
  }

  MissionRegistry registry_;
  std::unique_ptr<sim::Scenario> scenario_;
  sim::SitlRunnerParams sitl_;
};

TEST_F(BuiltinMissionsTest, EveryScenarioHasAMissionAndTheGapMissionReadsItsSection) {
  for (const char* scenario : {"gap", "gapflyt", "led", "tags", "forest"}) {
    EXPECT_NO_THROW(registry_.DefaultFor(scenario)) << scenario;
  }
  EXPECT_EQ(registry_.DefaultFor("gap"), "gap");
  EXPECT_EQ(registry_.DefaultFor("led"), "led_hover");
  Load("gap");
  EXPECT_EQ(Create("gap", {"mission.hover_s=0.7"})->autopilot().name(), "gap_mission");
  try {
    Create("gap", {"mission.hover_ss=0.7"});
    FAIL() << "a misspelt mission key was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("hover_ss"));
  }
  EXPECT_THROW(Create("gap", {"mission.hover_s=-1"}), std::invalid_argument);
  try {
    Create("no_such_mission", {});
    FAIL() << "an unknown mission was created";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("led_hover"));  // lists the known ones
  }
}

// `aperture sim forest` without --duration flies long enough to reach the goal (the 10 s default
// ended every forest flight short of it): the distance at no more than bench mononav's slowest
// mean speed (0.40 m/s), and no absurd cap either.
TEST_F(BuiltinMissionsTest, ForestFliesLongEnoughToReachItsGoal) {
  Load("forest");
  for (const Eigen::Vector3d& goal_W : {Eigen::Vector3d(6.0, 0.0, 1.5),
                                        Eigen::Vector3d(22.0, 3.0, 1.5)}) {
    char item[96];
    std::snprintf(item, sizeof(item), "mission.goal_W=[%g, %g, %g]", goal_W.x(), goal_W.y(),
                  goal_W.z());
    const std::unique_ptr<MissionFlight> flight = Create("forest", {item});
    const double distance_m = (goal_W - sitl_.initial_state.p_WB).norm();
    EXPECT_GE(flight->MinimumDurationS(), distance_m / 0.40) << item;
    EXPECT_LE(flight->MinimumDurationS(), distance_m / 0.2 + 10.0) << item;
  }
}

TEST_F(BuiltinMissionsTest, GroundTruthHoverIsScoredOnItsDistanceFromTheStart) {
  Load("forest");
  std::unique_ptr<MissionFlight> flight = Create("hover", {});
  sim::SitlResult result;
  control::QuadState state;
  state.p_WB = sitl_.initial_state.p_WB;
  result.trajectory = {state, state};
  EXPECT_TRUE(flight->Evaluate(result).passed);
  result.trajectory[1].p_WB.x() += 0.3;  // drifted 30 cm
  const MissionEvaluation drifted = flight->Evaluate(result);
  EXPECT_FALSE(drifted.passed);
  EXPECT_NEAR(drifted.figures["hover_error_m"]["max"].get<double>(), 0.3, 1e-12);
  result.trajectory[1].p_WB = state.p_WB;
  result.collision = sim::Collision{};
  EXPECT_FALSE(flight->Evaluate(result).passed);
}

}  // namespace
}  // namespace aperture::experiments
