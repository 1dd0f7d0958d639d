#pragma once
// Builds the vision gap mission (planning/gap_mission/gap_mission.h) from what the simulated
// vehicle would know on hardware: the scenario's forward camera (model and mount T_BC), the
// pattern sizes of its gap, the vehicle model and the IMU's noise specification. Nothing about
// the true gap pose or the ground truth goes in. Used by `aperture sim gap` and `aperture bench
// gap`; lives in experiments/ because it reads sim/ types and planning/ must not depend on sim/.
//
//   const sim::Scenario scenario = sim::BuildScenario(scenario_params);
//   planning::GapMissionParams params = GapMissionParamsFor(scenario, sitl_params.imu);
//   (optional: overrides, e.g. config::ParamReader `mission` section, planning's LoadParams)
//   std::unique_ptr<planning::GapMission> mission =
//       MakeGapMission(scenario, sitl_params.dynamics.vehicle, params);
#include <memory>
#include <string>

#include "control/vehicle_parameters.h"
#include "planning/gap_mission/gap_mission.h"
#include "sim/scenario/scenario.h"
#include "sim/sensors/imu_sensor.h"

namespace aperture::experiments {

// Index of the camera named "front", else of the first body-mounted one (the forward camera a
// vision mission flies with). Throws std::invalid_argument naming the scenario and `mission`
// when the scenario has no body-mounted camera.
int ForwardCameraIndex(const sim::Scenario& scenario, const std::string& mission);

// `base` with the scenario-derived fields replaced: detector pattern sizes (gap.opening_m,
// pattern_inner_m, pattern_outer_m), camera_id (the camera named "front", else the first
// body-mounted one) and the filter's IMU noise densities and random walks (from `imu`). Throws
// std::invalid_argument when the scenario has no body-mounted camera.
planning::GapMissionParams GapMissionParamsFor(const sim::Scenario& scenario,
                                               const sim::ImuSensorParams& imu,
                                               const planning::GapMissionParams& base = {});

// The mission for the scenario camera params.camera_id (its model and mount T_BC). Throws
// std::invalid_argument when that camera does not exist or is not body-mounted, or (through the
// mission) for invalid params.
std::unique_ptr<planning::GapMission> MakeGapMission(const sim::Scenario& scenario,
                                                     const control::VehicleParameters& vehicle,
                                                     const planning::GapMissionParams& params);

}  // namespace aperture::experiments
