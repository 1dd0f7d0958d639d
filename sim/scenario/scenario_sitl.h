#pragma once
// Glue from a Scenario to the lockstep SITL runner (sim/sitl/sitl_runner.h): its cameras become
// SitlCameras (model, mount, rate, effects, render options), its start pose the initial state,
// and a before_render hook keeps objects attached to the body (e.g. the LED target) on the
// vehicle.
//
//   Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig("gap", files, sets)));
//   SitlRunnerParams params;
//   ConfigureSitlFromScenario(scenario, &params);   // after params.SetSeed(), if used: SetSeed
//                                                   // replaces the cameras' noise seeds
//   SitlRunner runner(params, &scenario.scene());
//   SitlResult result = runner.Run(autopilot, MakeScenarioHooks(&scenario));
#include "sim/scenario/scenario.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::sim {

SitlCamera MakeSitlCamera(const ScenarioCamera& camera);

// Replaces params->cameras with the scenario's (in order: index = Frame::camera_id, with their
// rates, latencies and drop probabilities), sets the initial position and attitude to the
// scenario's start pose (velocity and rates zero) and the disturbances to the scenario's, replaces
// params->dynamics / imu / range / collision and the loop fields (rates, latencies, range_enabled,
// start_hovering) with the scenario's blocks of those keys where it has them (scenario_params.h),
// and adds the body-attached objects to params->collision.ignored_objects. Call SetSeed() after
// this: it replaces every noise seed, including those of the imu / range blocks.
void ConfigureSitlFromScenario(const Scenario& scenario, SitlRunnerParams* params);

// Hooks whose before_render moves the scenario's body-attached objects to the vehicle pose.
// `scenario` must outlive the run.
SitlHooks MakeScenarioHooks(Scenario* scenario);

}  // namespace aperture::sim
