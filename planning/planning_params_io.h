#pragma once
// YAML loaders (config::ParamReader, STYLE.md 6) for the narrow-gap planning parameters. Keys are
// the struct field names (they carry their units); absent keys keep the in-class defaults;
// unknown keys are rejected with the file, line and the known keys. Each loader ends with the
// struct's Validate(), so a loaded struct is always usable.
//
//   traverse:                       # TraverseParameters, problem (6)
//     max_start_speed_mps: 3.0
//     min_start_distance_m: 0.25
//   approach:                       # ApproachPlannerParameters, Sec. II-C..E
//     start_offset_min_A: [1.0, -1.5, -1.0]
//     start_offset_max_A: [4.0, 1.5, 1.0]
//     start_counts: [7, 7, 5]
//     duration_min_s: 1.0
//     duration_count: 8
//     min_height_m: 0.3             # omit for no floor
//     limits: {min_thrust_mps2: 5, max_thrust_mps2: 30, max_body_rate_radps: 10}
//
// All throw std::invalid_argument naming where the bad value is and what is expected.
#include "config/param_reader.h"
#include "planning/approach_planner.h"
#include "planning/primitive_feasibility.h"
#include "planning/traverse_trajectory.h"

namespace aperture::planning {

void LoadParams(config::ParamReader& reader, FeasibilityLimits* params);
void LoadParams(config::ParamReader& reader, TraverseParameters* params);
void LoadParams(config::ParamReader& reader, ApproachPlannerParameters* params);

}  // namespace aperture::planning
