#pragma once
// Mission `gap` (seed 000): the vision gap mission (planning/gap_mission/gap_mission.h) built
// from a `gap` scenario (experiments/gap/gap_mission_factory.h: camera, mount, pattern sizes,
// IMU specification; `mission.*` overrides GapMissionParams fields) and scored by the one gap
// evaluator (experiments/gap/gap_trial_evaluation.h) that `aperture bench gap` uses too.
//
// Figures (summary.json "mission"): phase, status, abort_reason, phase_starts, detection and
// fusion counts, the evaluator's success and failure_reason, crossing, error_at_gap (Table I
// analog), the traverse plan and the traverse start split into estimation and tracking errors.
#include <memory>

#include "experiments/missions/mission_registry.h"

namespace aperture::experiments {

std::unique_ptr<MissionFlight> MakeGapMissionFlight(const MissionContext& context);

}  // namespace aperture::experiments
