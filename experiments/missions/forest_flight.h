#pragma once
// Mission `forest` (seed 003, issue 17): planning::ForestMission (monocular depth -> EDT ->
// waypoint -> minimum-time B-spline -> flatness/attitude control, replanned every frame) built
// from a `forest` scenario, and scored by EvaluateForestFlight
// (experiments/missions/forest_evaluation.h) that `aperture bench mononav` uses too.
//
// From the scenario: the forward colour camera (cameras.front, color: true) and its mount, the
// goal (forest.goal_m: what the vehicle is told to fly to), the IMU specification for the filter.
// `mission.*` overrides ForestMissionParams (planning/mono_nav/forest_mission_params_io.h); the
// keys odometry.{rate_hz, position_sigma_m, rotation_sigma_rad} configure the odometry source.
//
// Odometry source in SITL: sim::OdometrySensor (sim/sensors/odometry_sensor.h), noisy ground-truth
// body poses at 50 Hz (2 cm, 0.5 deg white noise, no drift) standing in for the vehicle's VIO /
// optical-flow EKF; the mission fuses them with the IMU in perception::PoseFusion. The autopilot
// the SITL flies is a thin adapter that feeds the sensor from ground truth and forwards every
// other call to the mission, which itself never sees ground truth.
//
// Figures (summary.json "mission"): success, reached_goal, collision, failure_reason,
// time_to_goal_s, path_length_m, min_clearance_m (+ nearest_obstacle), final_distance_m,
// replans (Table II), frames, frames_without_path, recoveries (back-offs and look-asides),
// turns_to_goal, perception_ms / planning_ms (thread CPU per frame: mean, median, max), fusion
// counts, goal_m, ego_dynamic, waypoint_order.
#include <memory>

#include "experiments/missions/forest_evaluation.h"
#include "experiments/missions/mission_registry.h"
#include "planning/mono_nav/forest_mission.h"

namespace aperture::experiments {

std::unique_ptr<MissionFlight> MakeForestFlight(const MissionContext& context);

}  // namespace aperture::experiments
