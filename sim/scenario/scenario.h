#pragma once
// Scenario: a simulator world built from ScenarioParams (scenario_params.h): the Scene (objects,
// lighting), the cameras (model from perception's camera factory, mount, rate, sensor effects,
// render options) and the vehicle's start pose. Every random choice (textures, placements, pose
// and lighting jitter, sensor noise seeds) is a pure function of params.seed, so the same params
// give bit-identical frames.
//
// Build one from a built-in name plus overrides (what `aperture render` and SITL do):
//   config::ConfigTree tree = ScenarioConfig("gap", config_files, {"gap.roll_deg=30", "seed=4"});
//   Scenario scenario = BuildScenario(LoadScenarioParams(tree));
//   const ScenarioCamera& camera = scenario.camera("front");
//   scenario.SetVehiclePose(T_WB);                 // moves objects attached to the body
//   CapturedFrame f = camera.effects.Capture(caster, scenario.scene(), *camera.model,
//                         [&](double) { return camera.T_WC(T_WB); }, t_s, index, camera.render);
//
// Object names: the gap panel is "gap" (T_WO = T_WG, origin at the opening centre), the LED
// target "led_target" (T_WO = T_WB), tags "tag<id>" (AprilTag object frame), in `tags` the
// ground robot "robot", the goal "goal", obstacles "fixed<k>" and "movable<k>" (tag ids:
// TagsSceneParams); walls/ground/trees have descriptive names.
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/config_tree.h"
#include "perception/camera/camera_model.h"
#include "sim/render/camera_effects.h"
#include "sim/render/ray_caster.h"
#include "sim/scenario/scenario_params.h"
#include "sim/scene/scene.h"

namespace aperture::sim {

struct ScenarioCamera {
  std::string name;
  std::shared_ptr<const perception::CameraModel> model;
  // Exactly one is set: T_BC (p_B = T_BC * p_C) for a camera on the body, T_WC_fixed for a camera
  // fixed in the world (the scenario's `mount_on_body`).
  std::optional<Eigen::Isometry3d> T_BC = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Isometry3d> T_WC_fixed;
  double rate_hz = 30.0;
  double latency_s = 0.0;         // SITL delivery latency [s]
  double drop_probability = 0.0;  // SITL frame drops, in [0, 1)
  CameraEffects effects{CameraEffectsParams{}};
  RenderOptions render;

  // Camera pose for the vehicle at T_WB (ignored for a world-mounted camera).
  Eigen::Isometry3d T_WC(const Eigen::Isometry3d& T_WB) const {
    return T_BC ? Eigen::Isometry3d(T_WB * *T_BC) : *T_WC_fixed;
  }
};

class Scenario {
 public:
  const std::string& kind() const { return params_.scenario; }
  const ScenarioParams& params() const { return params_; }
  Scene& scene() { return scene_; }
  const Scene& scene() const { return scene_; }
  const std::vector<ScenarioCamera>& cameras() const { return cameras_; }
  // Throws std::invalid_argument listing the cameras for an unknown name.
  const ScenarioCamera& camera(const std::string& name) const;
  // The camera `aperture render` uses: trajectory.camera, else the first one.
  const ScenarioCamera& render_camera() const;
  const Eigen::Isometry3d& T_WB_start() const { return T_WB_start_; }

  // Makes the object move with the vehicle body: SetVehiclePose sets its T_WO = T_WB * T_BO.
  void AttachToBody(int object_id, const Eigen::Isometry3d& T_BO);
  // Moves every object attached to the vehicle body (T_WO = T_WB * T_BO).
  void SetVehiclePose(const Eigen::Isometry3d& T_WB);
  // Names of the body-attached objects (not obstacles for the vehicle carrying them).
  std::vector<std::string> AttachedObjectNames() const;

 private:
  friend Scenario BuildScenario(const ScenarioParams& params);
  struct Attached {
    int object_id;
    Eigen::Isometry3d T_BO;
  };

  ScenarioParams params_;
  Scene scene_;
  std::vector<ScenarioCamera> cameras_;
  std::vector<Attached> attached_;
  Eigen::Isometry3d T_WB_start_ = Eigen::Isometry3d::Identity();
};

// Builds the world. Throws std::invalid_argument naming the field for inconsistent parameters
// (e.g. an invalid camera, a duplicate object name, an unknown tag family).
Scenario BuildScenario(const ScenarioParams& params);

// Built-in scenario names and their YAML text (the defaults `aperture render NAME` starts from).
std::vector<std::string> BuiltinScenarioNames();
// Throws std::invalid_argument listing the names for an unknown one.
const std::string& BuiltinScenarioYaml(const std::string& name);

// Built-in defaults of `name` < config_files < set_items (config_tree.h layering).
config::ConfigTree ScenarioConfig(const std::string& name,
                                  const std::vector<std::string>& config_files = {},
                                  const std::vector<std::string>& set_items = {});
// Strictly loads the whole tree (unknown keys throw with file:line and the known keys).
ScenarioParams LoadScenarioParams(const config::ConfigTree& tree);

// Writes into `tree` the effective SITL blocks of `params` in full (scenario_params.h:
// disturbances, dynamics, imu, range, collision and the sitl loop fields; a block the scenario
// does not have: the in-class defaults ConfigureSitlFromScenario keeps), so that the tree names
// every simulator value a run used and loads back to the same ScenarioParams blocks.
void PutEffectiveSitlBlocks(const ScenarioParams& params, config::ConfigTree* tree);

}  // namespace aperture::sim
