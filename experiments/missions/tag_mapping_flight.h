#pragma once
// Mission `map` (issue 15, item 3; paper D's mapping flight), the default of scenario `tags`:
// planning::TagMappingAutopilot (lawn-mower coverage at the height that keeps the smallest tag
// resolvable, the downward camera's frames through the apriltag front end into an incremental
// TagMap) over the `tags` field, scored on the scene's ground truth by EvaluateTagMap
// (experiments/tags/tag_map_evaluation.h, as `aperture bench tags` scores its map).
//
// From the scenario: the downward camera (cameras.down, body-mounted) and its mount, the field
// and its tags' sizes and surface heights (experiments/tags/tags_scenario_field.h: no positions),
// the IMU specification for the filter. `mission.*` overrides planning::TagMappingParams
// (planning/tag_mapping/tag_mapping_params_io.h); odometry.{rate_hz, position_sigma_m,
// rotation_sigma_rad} configure the odometry source.
//
// State estimation in SITL: as the forest mission, sim::OdometrySensor (noisy ground-truth body
// poses at 50 Hz, 2 cm / 0.5 deg white noise, no drift) fused with the IMU
// (experiments/missions/odometry_adapter.h). The map takes only the images and, per image, that
// estimate's gravity direction and camera pose (the onboard estimate paper D's images carry);
// it never sees ground truth.
//
// Passed: no collision, the flight finished, every tag of the field mapped, position RMS after
// optimization <= 2 cm (the acceptance) and no flipped tag (rotation > 10 deg off).
// Figures (summary.json "mission"): passed first, then map_rms_after_m, map_rms_before_m,
// tags_mapped / tags_total, flipped_tags, flight_time_s, height_m, tracks, track_spacing_m,
// frames, the map's graph counts and solve time, map_tags (per tag). Files: tag_map.yaml and
// tag_map.png (perception/tags/tag_map_writer.h), tag_map_errors.csv (per mapped tag: true
// position in the origin tag's frame, error after and before optimization, rotation error,
// flipped, sigma, observations). The video shows the map growing (inset, lower right).
#include <memory>
#include <string>

#include "experiments/missions/mission_registry.h"
#include "planning/tag_mapping/tag_mapping_autopilot.h"

namespace aperture::experiments {

// The mapping parameters' defaults for the scenario: its downward camera (std::invalid_argument
// naming `mission` without one) and the IMU noise of the vehicle.
planning::TagMappingParams TagsMappingParams(const MissionContext& context,
                                             const std::string& mission);
// The mapping autopilot over the scenario's tag field with its downward camera.
std::unique_ptr<planning::TagMappingAutopilot> MakeTagsMappingAutopilot(
    const MissionContext& context, const planning::TagMappingParams& params);

std::unique_ptr<MissionFlight> MakeTagMappingFlight(const MissionContext& context);

}  // namespace aperture::experiments
