#include "sim/scenario/scenario_sitl.h"

namespace aperture::sim {

SitlCamera MakeSitlCamera(const ScenarioCamera& camera) {
  SitlCamera sitl;
  sitl.name = camera.name;
  sitl.model = camera.model;
  if (camera.mount_on_body) {
    sitl.T_BC = camera.T_mount;
  } else {
    sitl.T_WC_fixed = camera.T_mount;
  }
  sitl.rate_hz = camera.rate_hz;
  sitl.latency_s = camera.latency_s;
  sitl.effects = camera.effects.params();
  sitl.render = camera.render;
  return sitl;
}

void ConfigureSitlFromScenario(const Scenario& scenario, SitlRunnerParams* params) {
  params->cameras.clear();
  for (const ScenarioCamera& camera : scenario.cameras()) {
    params->cameras.push_back(MakeSitlCamera(camera));
  }
  for (const std::string& name : scenario.AttachedObjectNames()) {
    params->collision.ignored_objects.push_back(name);
  }
  const Eigen::Isometry3d& T_WB = scenario.T_WB_start();
  params->initial_state.p_WB = T_WB.translation();
  params->initial_state.q_WB = Eigen::Quaterniond(T_WB.linear());
  params->initial_state.v_W.setZero();
  params->initial_state.omega_B.setZero();
  params->disturbances = scenario.params().disturbances;
}

SitlHooks MakeScenarioHooks(Scenario* scenario) {
  SitlHooks hooks;
  hooks.before_render = [scenario](double, const control::QuadState& state) {
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.linear() = state.q_WB.toRotationMatrix();
    T_WB.translation() = state.p_WB;
    scenario->SetVehiclePose(T_WB);
  };
  return hooks;
}

}  // namespace aperture::sim
