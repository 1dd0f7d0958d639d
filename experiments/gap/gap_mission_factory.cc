#include "experiments/gap/gap_mission_factory.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace aperture::experiments {

int ForwardCameraIndex(const sim::Scenario& scenario, const std::string& mission) {
  const std::vector<sim::ScenarioCamera>& cameras = scenario.cameras();
  int first_on_body = -1;
  for (int i = 0; i < static_cast<int>(cameras.size()); ++i) {
    if (!cameras[i].T_BC) continue;
    if (cameras[i].name == "front") return i;
    if (first_on_body < 0) first_on_body = i;
  }
  if (first_on_body < 0) {
    throw std::invalid_argument("scenario '" + scenario.kind() +
                                "' has no body-mounted camera for the " + mission +
                                " mission: add a forward camera (cameras.front)");
  }
  return first_on_body;
}

planning::GapMissionParams GapMissionParamsFor(const sim::Scenario& scenario,
                                               const sim::ImuSensorParams& imu,
                                               const planning::GapMissionParams& base) {
  planning::GapMissionParams params = base;
  const sim::GapParams& gap = scenario.params().gap;
  static_cast<perception::GapPattern&>(params.detector) = gap.Pattern();  // tuning kept
  params.camera_id = ForwardCameraIndex(scenario, "gap");
  params.filter.accel_noise_density = imu.accel_noise_density;
  params.filter.gyro_noise_density = imu.gyro_noise_density;
  params.filter.accel_bias_random_walk = imu.accel_bias_random_walk;
  params.filter.gyro_bias_random_walk = imu.gyro_bias_random_walk;
  return params;
}

std::unique_ptr<planning::GapMission> MakeGapMission(const sim::Scenario& scenario,
                                                     const control::VehicleParameters& vehicle,
                                                     const planning::GapMissionParams& params) {
  const std::vector<sim::ScenarioCamera>& cameras = scenario.cameras();
  if (params.camera_id < 0 || params.camera_id >= static_cast<int>(cameras.size()) ||
      !cameras[params.camera_id].T_BC) {
    throw std::invalid_argument("gap mission camera_id " + std::to_string(params.camera_id) +
                                " is not a body-mounted camera of scenario '" + scenario.kind() +
                                "' (it has " + std::to_string(cameras.size()) + " cameras)");
  }
  const sim::ScenarioCamera& camera = cameras[params.camera_id];
  return std::make_unique<planning::GapMission>(params, camera.model, *camera.T_BC, vehicle);
}

}  // namespace aperture::experiments
