#include "planning/planning_params_io.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace aperture::planning {

void LoadParams(config::ParamReader& reader, FeasibilityLimits* params) {
  reader.Read("min_thrust_mps2", &params->min_thrust_mps2);
  reader.Read("max_thrust_mps2", &params->max_thrust_mps2);
  reader.Read("max_body_rate_radps", &params->max_body_rate_radps);
  reader.Read("min_section_duration_s", &params->min_section_duration_s);
  reader.Read("gravity_mps2", &params->gravity_mps2);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, TraverseParameters* params) {
  reader.Read("max_start_speed_mps", &params->max_start_speed_mps);
  reader.Read("min_start_distance_m", &params->min_start_distance_m);
  reader.Read("max_start_distance_m", &params->max_start_distance_m);
  reader.Read("max_time_to_gap_s", &params->max_time_to_gap_s);
  reader.Read("gravity_mps2", &params->gravity_mps2);
  reader.Read("relative_tolerance", &params->relative_tolerance);
  reader.Read("max_evaluations", &params->max_evaluations);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

void LoadParams(config::ParamReader& reader, ApproachPlannerParameters* params) {
  reader.Read("start_offset_min_A", &params->start_offset_min_A);
  reader.Read("start_offset_max_A", &params->start_offset_max_A);
  if (reader.Has("start_counts")) {
    std::vector<int> counts;
    reader.Read("start_counts", &counts);
    if (counts.size() != 3) {
      throw std::invalid_argument(
          reader.Where("start_counts") + ": key '" + reader.FullKey("start_counts") +
          "' expects 3 integers [x, y, z], got " + std::to_string(counts.size()));
    }
    params->start_counts = Eigen::Vector3i(counts[0], counts[1], counts[2]);
  }
  reader.Read("duration_min_s", &params->duration_min_s);
  reader.Read("duration_max_s", &params->duration_max_s);
  reader.Read("duration_count", &params->duration_count);
  reader.Read("samples_per_candidate", &params->samples_per_candidate);
  reader.Read("view_angle_normalization_rad", &params->view_angle_normalization_rad);
  reader.Read("start_distance_normalization_m", &params->start_distance_normalization_m);
  reader.Read("max_view_angle_rad", &params->max_view_angle_rad);
  reader.Read("optical_axis_B", &params->optical_axis_B);
  reader.Read("min_height_m", &params->min_height_m);
  reader.ReadSection("limits", &params->limits);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

}  // namespace aperture::planning
