// Built-in scenarios as YAML text: the defaults `aperture render NAME` and SITL start from. Keys
// and meaning: scenario_params.h. Camera poses: forward camera T_BC rpy [-90, 0, -90] puts
// z_C along x_B (x_C = -y_B, y_C = -z_B); downward camera rpy [180, 0, -90] puts z_C along -z_B
// with x_C = -y_B (image right = body right) and y_C = -x_B.
#include <map>
#include <stdexcept>

#include "sim/scenario/scenario.h"
#include "sim/sim_params_io.h"

namespace aperture::sim {
namespace {

// Seed 000: 80 x 28 cm gap, 752 x 480 monochrome 180 deg fisheye, approach from 5 m to 1 m.
constexpr const char* kGapYaml = R"(scenario: gap
seed: 0
lighting: {ambient: 0.45, directional: 0.55, direction_W: [0.4, 0.3, -1.0]}
vehicle: {start: {p_m: [0.0, 0.0, 1.5], rpy_deg: [0, 0, 0]}}
cameras:
  front:
    model: equidistant
    width: 752
    height: 480
    fov_deg: 180
    pose: {p_m: [0.1, 0.0, 0.0], rpy_deg: [-90, 0, -90]}
    rate_hz: 50
    read_noise_sigma: 0.004
    full_well_electrons: 5000
    supersampling: 2
trajectory: {kind: line, frames: 60, end_p_m: [4.0, 0.0, 1.5], amplitude_m: 0.4}
gap:
  center_W: [5.0, 0.0, 1.5]
  roll_deg: 0
  pitch_deg: 0
  panel_m: [1.8, 1.2]
)";

// Seed 002: foreground wall ~2.6 m, background ~5.7 m, lateral motion for parallax; `shape`
// picks one of the five opening kinds (ellipse | polygon | triangle | notched | star).
constexpr const char* kGapFlytYaml = R"(scenario: gapflyt
seed: 0
vehicle: {start: {p_m: [0.0, 0.0, 1.5], rpy_deg: [0, 0, 0]}}
cameras:
  front:
    model: pinhole
    width: 640
    height: 480
    fov_deg: 80
    pose: {p_m: [0.1, 0.0, 0.0], rpy_deg: [-90, 0, -90]}
    rate_hz: 30
trajectory: {kind: scan, frames: 40, end_p_m: [0.4, 0.0, 1.5], amplitude_m: 0.3, cycles: 1}
gapflyt:
  foreground_x_m: 2.6
  background_x_m: 5.7
  shape: polygon
  center_m: [0.0, 1.5]
  size_m: [1.0, 0.8]
)";

// Seed 001 paper C: quadrotor with 5 infrared LEDs over a static upward-looking camera.
constexpr const char* kLedYaml = R"(scenario: led
seed: 0
vehicle: {start: {p_m: [0.0, 0.0, 2.0], rpy_deg: [0, 0, 0]}}
cameras:
  ground:
    model: pinhole
    width: 752
    height: 480
    fov_deg: 90
    mount_on_body: false
    pose: {p_m: [0.0, 0.0, 0.05], rpy_deg: [0, 0, 0]}
    # C.4.3: pose estimates at 40 Hz; ~25 ms from the end of exposure to the vehicle (tracking
    # a few ms, Table C.2, plus the radio link from the ground robot).
    rate_hz: 40
    latency_s: 0.025
    infrared: true
    read_noise_sigma: 0.01
trajectory: {kind: random, frames: 40, amplitude_m: 0.4, angle_amplitude_deg: 20}
led:
  # The led front end's built-in layout (perception/led/led_configuration.cc), so a rendered
  # sequence replays through `aperture run --frontends led` without a config file.
  leds: [[0.0, 0.105, 0.0], [0.1, 0.01, 0.0], [0.02, -0.09, -0.03], [-0.09, -0.04, 0.0], [-0.04, 0.04, -0.08]]
  false_spots: 0
# `aperture sim led` (C.4.3: "pushed or flies outdoors with unpredictable winds"): gusts of
# 1-2 m/s from changing directions over a minute, and one push of 0.45 N s (1 m/s on the
# 0.45 kg vehicle) at 6 s.
disturbances:
  gusts: [[2, 2, 1.5, 0, 0], [9, 3, 0, -2, 0], [16, 2, -1.5, 1, 0], [24, 4, 1, 1.5, 0],
          [33, 3, -2, 0, 0], [41, 2, 0, 2, 0], [48, 3, 1.5, -1.5, 0], [55, 3, -1, -1, 0]]
  pushes: [[6, 0.45, 0, 0]]
)";

// Seed 001 paper D (D.3.3): 4 x 6 m tagged area with fixed and movable obstacles, a goal and the
// ground robot, seen by a downward camera.
constexpr const char* kTagsYaml = R"(scenario: tags
seed: 0
vehicle: {start: {p_m: [2.0, 1.0, 2.5], rpy_deg: [0, 0, 90]}}
cameras:
  down:
    model: pinhole
    width: 640
    height: 480
    fov_deg: 90
    pose: {p_m: [0.0, 0.0, -0.05], rpy_deg: [180, 0, -90]}
    rate_hz: 30
    supersampling: 3  # edges at their sub-pixel positions: the tag map needs them (issue 15)
trajectory: {kind: line, frames: 40, end_p_m: [2.0, 5.0, 2.5]}
tags:
  area_m: [4.0, 6.0]
  family: tag36h11
  tag_size_m: 0.25
  goal_xy_m: [3.5, 5.5]
  fixed_obstacles: 3
  movable_obstacles: 3
)";

// Seed 003: trunks, boxes and grass; flight along x_W through a corridor.
constexpr const char* kForestYaml = R"(scenario: forest
seed: 0
lighting: {ambient: 0.4, directional: 0.6, direction_W: [0.5, -0.3, -1.0]}
vehicle: {start: {p_m: [0.0, 0.0, 1.5], rpy_deg: [0, 0, 0]}}
cameras:
  front:
    model: pinhole
    width: 640
    height: 480
    fov_deg: 90
    pose: {p_m: [0.1, 0.0, 0.0], rpy_deg: [-90, 0, -90]}
    rate_hz: 30
    color: true
trajectory: {kind: line, frames: 60, end_p_m: [20.0, 0.0, 1.5]}
forest:
  trees: 40
  boxes: 6
  goal_m: [22.0, 0.0, 1.5]
)";

const std::map<std::string, std::string>& Builtins() {
  static const std::map<std::string, std::string> builtins{{"gap", kGapYaml},
                                                           {"gapflyt", kGapFlytYaml},
                                                           {"led", kLedYaml},
                                                           {"tags", kTagsYaml},
                                                           {"forest", kForestYaml}};
  return builtins;
}

}  // namespace

std::vector<std::string> BuiltinScenarioNames() {
  std::vector<std::string> names;
  for (const auto& [name, yaml] : Builtins()) names.push_back(name);
  return names;
}

const std::string& BuiltinScenarioYaml(const std::string& name) {
  const auto it = Builtins().find(name);
  if (it == Builtins().end()) {
    std::string known;
    for (const auto& [known_name, yaml] : Builtins())
      known += (known.empty() ? "" : ", ") + known_name;
    throw std::invalid_argument("unknown scenario '" + name + "'; built-in scenarios: " + known);
  }
  return it->second;
}

config::ConfigTree ScenarioConfig(const std::string& name,
                                  const std::vector<std::string>& config_files,
                                  const std::vector<std::string>& set_items) {
  return config::ConfigTree::FromCommandLine(BuiltinScenarioYaml(name), config_files, set_items);
}

ScenarioParams LoadScenarioParams(const config::ConfigTree& tree) {
  config::ParamReader root = tree.Reader();
  ScenarioParams params;
  LoadParams(root, &params);
  root.RejectUnknownKeys();
  return params;
}

void PutEffectiveSitlBlocks(const ScenarioParams& params, config::ConfigTree* tree) {
  const SitlRunnerParams defaults;
  tree->PutParams("disturbances", params.disturbances);
  tree->PutParams("dynamics", params.dynamics.value_or(defaults.dynamics));
  tree->PutParams("imu", params.imu.value_or(defaults.imu));
  tree->PutParams("range", params.range.value_or(defaults.range));
  tree->PutParams("collision", params.collision.value_or(defaults.collision));
  tree->PutParams("sitl", params.sitl.value_or(defaults));
}

}  // namespace aperture::sim
