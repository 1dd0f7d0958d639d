#pragma once
// YAML loader (config::ParamReader, STYLE.md 6) for GapMissionParams, the `mission` section of
// `aperture sim gap` (`--set mission.hover_s=0.5`). Keys are the field names; absent keys keep
// the defaults (or what the caller set before, e.g. the scenario's pattern sizes); unknown keys
// are rejected with their location and the known keys.
//
//   mission:
//     hover_s: 1.0
//     transfer_speed_mps: 1.5
//     detector: {canny_low: 40}          # GapDetectorParams (perception/gap)
//     filter: {mahalanobis_gate: 22.46}  # PoseImuFilterParams (perception/estimation)
//     traverse: {max_start_speed_mps: 3} # TraverseParameters (planning)
//     approach: {duration_min_s: 1.0}    # ApproachPlannerParameters (planning)
//
// The controller and recovery gains keep their Table A.2 defaults (no keys). Ends with
// GapMissionParams::Validate(); throws std::invalid_argument naming where the bad value is.
#include "config/param_reader.h"
#include "planning/gap_mission/gap_mission.h"

namespace aperture::planning {

void LoadParams(config::ParamReader& reader, GapMissionParams* params);

}  // namespace aperture::planning
