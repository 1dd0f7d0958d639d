#pragma once
// The vehicle of seed 000 Sec. III as a preset of the `gap` scenario (issue 21, item 4): 830 g,
// 55 x 12 cm (the largest length between propeller tips x the height). The paper gives no more,
// so the rest is ours scaled: Table A.2's arm (0.178 m) with propellers sized for the 55 cm
// diagonal span (radius 0.275 m - arm), a 12 cm tall body (sphere of radius 0.06 m), the thrust
// and torque maps and the inertia scaled by the mass ratio (the same thrust-to-weight ratio and
// angular accelerations). The controllers fly it as their model, like ours.
//
//   sim::ScenarioParams base = ...;       // the `gap` scenario with its overrides
//   UsePaperGapVehicle(&base);            // before BuildScenario / ConfigureSitlFromScenario
#include "sim/scenario/scenario_params.h"

namespace aperture::experiments {

constexpr double kPaperVehicleMassKg = 0.83;     // seed 000 Sec. III
constexpr double kPaperVehicleTipToTipM = 0.55;  // largest length between propeller tips
constexpr double kPaperVehicleHeightM = 0.12;

// Replaces the scenario's vehicle (dynamics.vehicle) and its collision geometry (collision
// radii) by the paper's as described above; keeps every other dynamics and collision field.
void UsePaperGapVehicle(sim::ScenarioParams* params);

}  // namespace aperture::experiments
