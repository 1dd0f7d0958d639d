#pragma once
// What a vehicle mapping the `tags` scenario is told of its field (sim::TagsSceneParams): the
// apriltag front end's settings for its tags, and the field for the coverage planner. Sizes and
// heights only, no placements: the map has to find where the tags are. Shared by
// `aperture bench tags` (mapping section) and the mapping flight (tag_mapping_flight.h).
#include <string>

#include "perception/tags/tag_front_end.h"
#include "planning/tag_mapping/tag_mapping_autopilot.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_params.h"

namespace aperture::experiments {

// The front end for the field's tags: tag_size_m for every tag but the movable obstacles'
// (movable_tag_size_m by id), detection at full resolution and the corner noise measured on the
// rendered tags (see the .cc).
perception::TagFrontEndParams TagsFieldFrontEndParams(const sim::TagsSceneParams& field);

// The field rectangle [0, area_m] (the origin tag at its corner), a tag class per surface a tag
// lies on (ground, goal mat, robot, fixed and movable obstacle tops), the largest pattern.
planning::TagField TagsFieldForMapping(const sim::TagsSceneParams& field);

// Index of the body-mounted camera "down" a `tags` mission flies with. Throws
// std::invalid_argument naming `mission` when the scenario is not `tags` or has no such camera.
int TagsDownCameraIndex(const sim::Scenario& scenario, const std::string& mission);

}  // namespace aperture::experiments
