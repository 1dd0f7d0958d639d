#pragma once
// Mission `gapflyt` (seed 002): the GapFlyt mission (planning/gapflyt/gapflyt_mission.h) built from
// a `gapflyt` scenario (the forward camera's model, mount and rate; `mission.*` overrides
// GapflytMissionParams, e.g. `--set mission.servo.law=pid`) and scored on ground truth by
// EvaluateGapflytFlight (experiments/gapflyt/gapflyt_evaluation.h), the evaluator `aperture bench
// gapflyt` and the tests use too.
//
// Figures (summary.json "mission"): law, phase, status, reason, phase_starts, scans, scan_statuses,
// frames_tracked, detection {t_s, overlap, false_negative, false_positive, detected (>= 0.75)},
// crossed, inside_opening, clearance_m (footprint to the edge), centre_to_edge_m,
// crossing_offset_m (from the opening's centroid, in the wall: right, down), time_to_cross_s
// (from the start), servo_to_cross_s (from the servo's start), crossing_speed_mps,
// failure_reason; passed = crossed inside the opening without a collision.
#include <memory>

#include "experiments/missions/mission_registry.h"

namespace aperture::experiments {

std::unique_ptr<MissionFlight> MakeGapflytFlight(const MissionContext& context);

}  // namespace aperture::experiments
