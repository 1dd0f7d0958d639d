#pragma once
// The missions aperture ships, registered by name (no self-registration: the application owns the
// registry, as with front ends):
//   gap        vision gap mission (seed 000), default of scenario `gap`
//              (experiments/missions/gap_mission_flight.h)
//   led_hover  LED-stabilized hover (thesis C.4.3), default of scenario `led`
//              (experiments/led/led_hover_flight.h)
//   hover      ground-truth hover at the start pose (sim/sitl/ground_truth_autopilot.h), the
//              default of the scenarios that have no mission of their own yet
//              (gapflyt, tags, forest)
#include "experiments/missions/mission_registry.h"

namespace aperture::experiments {

void RegisterBuiltinMissions(MissionRegistry& registry);

}  // namespace aperture::experiments
