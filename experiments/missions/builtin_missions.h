#pragma once
// The missions aperture ships, registered by name (no self-registration: the application owns the
// registry, as with front ends):
//   gap        vision gap mission (seed 000), default of scenario `gap`
//              (experiments/missions/gap_mission_flight.h)
//   led_hover  LED-stabilized hover (thesis C.4.3), default of scenario `led`
//              (experiments/led/led_hover_flight.h)
//   forest     monocular forest navigation (seed 003), default of scenario `forest`
//              (experiments/missions/forest_flight.h)
//   gapflyt    GapFlyt (seed 002), default of scenario `gapflyt`
//              (experiments/missions/gapflyt_flight.h)
//   map        tag mapping flight (seed 001, paper D), default of scenario `tags`
//              (experiments/missions/tag_mapping_flight.h)
//   hover      ground-truth hover at the start pose (sim/sitl/ground_truth_autopilot.h), the
//              reference flight of any scenario (--mission hover)
#include "experiments/missions/mission_registry.h"

namespace aperture::experiments {

void RegisterBuiltinMissions(MissionRegistry& registry);

}  // namespace aperture::experiments
