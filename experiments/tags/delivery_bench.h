#pragma once
// `aperture bench delivery` (issue 16, the closed loop; paper D Sec. D.7.2, "demonstrated more
// than 20 times"): seeded SITL flights of the ground-robot mission on random `tags` fields (the
// scenario places the robot, the obstacles and the goal per seed), one field per trial:
//   mission `deliver`  mapping flight, tag map, the robot's mission planned on the map, executed
//                      with odometry drift and relocalization while the quadrotor follows
//   mission `follow`   the same execution, planned on the scenario's true tag poses (no mapping
//                      flight: ~40 % of the CPU)
// in each configuration: `relocalize` (paper D: relocalized between segments) and `open_loop`
// (mission.robot_relocalize=false: the drift accumulates). A flight succeeds when the first-aid
// kit lies on the goal with no collision of the robot, its carried obstacle or the quadrotor, and
// the robot's tag stayed within 10 % of the image width of the image centre (the missions'
// Evaluate, experiments/missions/tag_follow_flight.h); a field on which the planner finds no
// mission is counted apart (fields_without_mission), not as a flight. Summary: success per
// configuration with the failures by cause and seed, the servo's offsets, the relocalizations'
// figures, and the acceptance (>= 95 % with relocalization).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/missions/fly_mission.h"
#include "output/html_report.h"

namespace aperture::experiments {

struct DeliveryBenchOptions {
  int trials = 50;                  // fields (scenario seeds first_seed ..)
  std::uint64_t first_seed = 1;     // scenario seed of the first field (also its sensors' noise)
  std::string mission = "deliver";  // deliver | follow
  std::vector<std::string> configurations;  // relocalize | open_loop; empty = relocalize
  // Overrides of the `tags` scenario and of the mission (`mission.*`), applied to every flight.
  std::vector<std::string> set_items;
  std::string flights_csv_path;  // one row per flight; empty = none

  void Validate() const;                                // std::invalid_argument naming the option
  std::vector<std::string> ConfigurationNames() const;  // in order; the default filled in
};

struct DeliveryFlight {
  std::string configuration;
  std::uint64_t seed = 0;
  MissionFlightRun run;
  // Why the flight failed in one word (success ""): no_mission, mapping, quadrotor_collision,
  // robot_contact, fail_safe, not_finished, kit_off_goal, servo_offset, error.
  std::string failure;
};

// Field `trial` (seed first_seed + trial) flown in every configuration, in order. A field on which
// the mission cannot be set up (e.g. no order of removals reaches the goal) is a failed flight.
std::vector<DeliveryFlight> FlyDeliveryField(const DeliveryBenchOptions& options, int trial);

// Fills summary "delivery" and "acceptance", writes flights_csv_path, adds the report's sections.
void WriteDeliverySections(const DeliveryBenchOptions& options,
                           const std::vector<DeliveryFlight>& flights, nlohmann::json* summary,
                           output::HtmlReport* report);

nlohmann::json DeliveryFlightToJson(const DeliveryFlight& flight);
DeliveryFlight DeliveryFlightFromJson(const nlohmann::json& json);

}  // namespace aperture::experiments
