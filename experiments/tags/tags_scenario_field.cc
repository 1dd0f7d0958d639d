#include "experiments/tags/tags_scenario_field.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "sim/scene/apriltag_object.h"

namespace aperture::experiments {

perception::TagFrontEndParams TagsFieldFrontEndParams(const sim::TagsSceneParams& field) {
  perception::TagFrontEndParams params;
  params.detection.families = {field.family};
  params.size_m = field.tag_size_m;
  // Tag ids of sim/scenario/scenario.cc BuildTags: 0 origin, 1 goal, 2 robot, then the fixed and
  // the movable obstacles.
  const int first_movable = 3 + field.fixed_obstacles;
  for (int k = 0; k < field.movable_obstacles; ++k) {
    params.sizes[first_movable + k] = field.movable_tag_size_m;
  }
  params.detection.quad_decimate = 1.0;  // the 0.1 m movable tags are ~13 px at 2.5 m
  // The rendered corners' error against the projected truth (bench tags, corner_error_*_px):
  // median ~0.11 px, 90 % ~0.22 px, partly systematic (0.1 m tags look ~0.13 px smaller per
  // corner; edges parallel to the pixel rows); the default 1 px would weight the tags 1/25
  // against gravity, 0.15 px (the white part alone) gave larger map errors on seeds 1-3.
  params.pose.refiner.detection_sigma_px = 0.3;
  return params;
}

planning::TagField TagsFieldForMapping(const sim::TagsSceneParams& field) {
  planning::TagField out;
  out.rectangle.max_W = field.area_m;
  // The origin tag lies on the ground; the goal mat, the robot and the obstacles carry theirs on
  // their tops.
  out.classes = {{field.tag_size_m, 0.0},
                 {field.tag_size_m, field.goal_size_m.z()},
                 {field.tag_size_m, field.robot_size_m.z()}};
  if (field.fixed_obstacles > 0) out.classes.push_back({field.tag_size_m, field.fixed_size_m.z()});
  double largest_m = field.tag_size_m;
  if (field.movable_obstacles > 0) {
    out.classes.push_back({field.movable_tag_size_m, field.movable_size_m.z()});
    largest_m = std::max(largest_m, field.movable_tag_size_m);
  }
  out.max_pattern_m = sim::AprilTagPatternSize(field.family, largest_m);
  return out;
}

int TagsDownCameraIndex(const sim::Scenario& scenario, const std::string& mission) {
  if (scenario.kind() != "tags") {
    throw std::invalid_argument("mission '" + mission +
                                "' flies over the tags field: fly it in scenario 'tags' (it was "
                                "given '" +
                                scenario.kind() + "')");
  }
  const std::vector<sim::ScenarioCamera>& cameras = scenario.cameras();
  for (int i = 0; i < static_cast<int>(cameras.size()); ++i) {
    if (cameras[i].name == "down" && cameras[i].T_BC) return i;
  }
  throw std::invalid_argument("scenario 'tags' has no body-mounted camera 'down' for mission '" +
                              mission + "': add one (cameras.down)");
}

}  // namespace aperture::experiments
