#pragma once
// Configuration descriptions (Serialize, config/param_archive.h) of the narrow-gap planning
// parameters: LoadParams(reader, &params) loads (config/yaml_read_archive.h), config::DumpParams
// dumps. Keys are the struct field names (they carry their units); absent keys keep the in-class
// defaults; unknown keys are rejected with the file, line and the known keys. Loading ends with the
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
//     min_height_m: 0.3             # -.inf (the default): no floor
//     limits: {min_thrust_mps2: 5, max_thrust_mps2: 30, max_body_rate_radps: 10}
//
// All throw std::invalid_argument naming where the bad value is and what is expected.
#include "config/yaml_read_archive.h"
#include "planning/approach_planner.h"
#include "planning/primitive_feasibility.h"
#include "planning/traverse_trajectory.h"

namespace aperture::planning {

template <typename Archive>
void Serialize(Archive* a, FeasibilityLimits* p) {
  a->Visit(APERTURE_NVP(p, min_thrust_mps2));
  a->Visit(APERTURE_NVP(p, max_thrust_mps2));
  a->Visit(APERTURE_NVP(p, max_body_rate_radps));
  a->Visit(APERTURE_NVP(p, min_section_duration_s));
  a->Visit(APERTURE_NVP(p, gravity_mps2));
}

template <typename Archive>
void Serialize(Archive* a, TraverseParameters* p) {
  a->Visit(APERTURE_NVP(p, max_start_speed_mps));
  a->Visit(APERTURE_NVP(p, min_start_distance_m));
  a->Visit(APERTURE_NVP(p, max_start_distance_m));
  a->Visit(APERTURE_NVP(p, max_time_to_gap_s));
  a->Visit(APERTURE_NVP(p, gravity_mps2));
  a->Visit(APERTURE_NVP(p, relative_tolerance));
  a->Visit(APERTURE_NVP(p, max_evaluations));
}

template <typename Archive>
void Serialize(Archive* a, ApproachPlannerParameters* p) {
  a->Visit(APERTURE_NVP(p, start_offset_min_A));
  a->Visit(APERTURE_NVP(p, start_offset_max_A));
  a->Visit(APERTURE_NVP(p, start_counts));
  a->Visit(APERTURE_NVP(p, duration_min_s));
  a->Visit(APERTURE_NVP(p, duration_max_s));
  a->Visit(APERTURE_NVP(p, duration_count));
  a->Visit(APERTURE_NVP(p, samples_per_candidate));
  a->Visit(APERTURE_NVP(p, view_angle_normalization_rad));
  a->Visit(APERTURE_NVP(p, start_distance_normalization_m));
  a->Visit(APERTURE_NVP(p, max_view_angle_rad));
  a->Visit(APERTURE_NVP(p, optical_axis_B));
  a->Visit(APERTURE_NVP(p, min_height_m));
  a->Visit(APERTURE_NVP(p, max_overshoot_m));
  a->Visit(APERTURE_NVP(p, limits));
}

}  // namespace aperture::planning
