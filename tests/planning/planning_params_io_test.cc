#include "planning/planning_params_io.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <stdexcept>
#include <string>

#include "planning/gap_mission/gap_mission_params_io.h"
#include "tests/support/param_round_trip.h"

namespace aperture::planning {
namespace {

TEST(PlanningParamsIo, LoadsEveryGroupAndKeepsDefaults) {
  const YAML::Node root = YAML::Load(R"(
traverse: {max_start_speed_mps: 2.5, min_start_distance_m: 0.4}
approach:
  start_counts: [3, 4, 2]
  start_offset_max_A: [5.0, 2.0, 1.0]
  min_height_m: 0.3
  limits: {max_thrust_mps2: 22.0}
)");
  config::ParamReader reader(root, "planning.yaml");
  TraverseParameters traverse;
  ApproachPlannerParameters approach;
  reader.ReadSection("traverse", &traverse);
  reader.ReadSection("approach", &approach);
  reader.RejectUnknownKeys();
  EXPECT_EQ(traverse.max_start_speed_mps, 2.5);
  EXPECT_EQ(traverse.min_start_distance_m, 0.4);
  EXPECT_EQ(traverse.max_time_to_gap_s, TraverseParameters().max_time_to_gap_s);
  EXPECT_EQ(approach.start_counts, Eigen::Vector3i(3, 4, 2));
  EXPECT_EQ(approach.start_offset_max_A, Eigen::Vector3d(5.0, 2.0, 1.0));
  EXPECT_EQ(approach.min_height_m, 0.3);
  EXPECT_EQ(approach.limits.max_thrust_mps2, 22.0);
  EXPECT_EQ(approach.limits.min_thrust_mps2, FeasibilityLimits().min_thrust_mps2);
}

// Unknown keys, malformed counts and values that fail Validate() name the file and the key.
TEST(PlanningParamsIo, RejectsBadValuesNamingTheKey) {
  const auto load_approach = [](const std::string& yaml) {
    config::ParamReader reader(YAML::Load(yaml), "planning.yaml");
    ApproachPlannerParameters approach;
    reader.ReadSection("approach", &approach);
  };
  const auto message_of = [&](const std::string& yaml) {
    try {
      load_approach(yaml);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message_of("approach: {durations_count: 3}").find("durations_count"),
            std::string::npos);
  EXPECT_NE(message_of("approach: {start_counts: [3, 4]}").find("start_counts"), std::string::npos);
  EXPECT_NE(message_of("approach: {limits: {max_thrust_mps2: 1.0}}").find("max_thrust_mps2"),
            std::string::npos);
  EXPECT_NE(message_of("approach: {duration_count: 0}").find("planning.yaml"), std::string::npos);
}

TEST(PlanningParamsIo, EveryStructRoundTripsThroughItsDump) {
  test_support::ExpectRoundTrip(FeasibilityLimits{});
  test_support::ExpectRoundTrip(TraverseParameters{});
  ApproachPlannerParameters approach;
  approach.min_height_m = 0.3;  // the default -inf has no perturbation
  test_support::ExpectRoundTrip(approach);
}

// The mission's whole configuration, including the controller and recovery gains the loader used
// to skip.
TEST(GapMissionParamsIo, RoundTripsWithControllerAndRecovery) {
  GapMissionParams mission;
  mission.approach.min_height_m = 0.3;
  test_support::ExpectRoundTrip(mission);
  config::ParamReader reader(
      YAML::Load("{controller: {p_xy_per_s2: 7}, recovery: {max_vertical_speed_mps: 0.4, "
                 "controller: {d_z_per_s: 5}}}"),
      "mission.yaml");
  GapMissionParams loaded;
  LoadParams(reader, &loaded);
  EXPECT_EQ(loaded.controller.p_xy_per_s2, 7.0);
  EXPECT_EQ(loaded.recovery.max_vertical_speed_mps, 0.4);
  EXPECT_EQ(loaded.recovery.controller.d_z_per_s, 5.0);
  EXPECT_EQ(loaded.controller.p_z_per_s2, control::PositionControllerParams().p_z_per_s2);
}

}  // namespace
}  // namespace aperture::planning
