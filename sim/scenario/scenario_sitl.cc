#include "sim/scenario/scenario_sitl.h"

namespace aperture::sim {

SitlCamera MakeSitlCamera(const ScenarioCamera& camera) {
  SitlCamera sitl;
  sitl.name = camera.name;
  sitl.model = camera.model;
  if (camera.T_BC) sitl.T_BC = *camera.T_BC;
  sitl.T_WC_fixed = camera.T_WC_fixed;
  sitl.rate_hz = camera.rate_hz;
  sitl.latency_s = camera.latency_s;
  sitl.drop_probability = camera.drop_probability;
  sitl.effects = camera.effects.params();
  sitl.render = camera.render;
  return sitl;
}

void ConfigureSitlFromScenario(const Scenario& scenario, SitlRunnerParams* params) {
  const ScenarioParams& scenario_params = scenario.params();
  if (scenario_params.dynamics) params->dynamics = *scenario_params.dynamics;
  if (scenario_params.imu) params->imu = *scenario_params.imu;
  if (scenario_params.range) params->range = *scenario_params.range;
  if (scenario_params.collision) params->collision = *scenario_params.collision;
  if (const std::optional<SitlRunnerParams>& loop = scenario_params.sitl) {
    params->dynamics_rate_hz = loop->dynamics_rate_hz;
    params->control_rate_hz = loop->control_rate_hz;
    params->command_latency_s = loop->command_latency_s;
    params->range_latency_s = loop->range_latency_s;
    params->estimate_latency_s = loop->estimate_latency_s;
    params->esc_delay_s = loop->esc_delay_s;
    params->range_enabled = loop->range_enabled;
    params->start_hovering = loop->start_hovering;
    params->flight_controller.low_level.torque_observer_time_constant_s =
        loop->flight_controller.low_level.torque_observer_time_constant_s;
  }
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
  params->disturbances = scenario_params.disturbances;
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
