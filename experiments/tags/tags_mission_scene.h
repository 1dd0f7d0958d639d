#pragma once
// The ground-robot mission scene (planning/ground_mission/, paper D Sec. D.4-D.5) of the `tags`
// scenario from the poses of its tags: the map the aerial robot builds (perception::TagMap's
// T_WT) or the scenario's truth (TagsScenarioTagPoses). Tag ids as sim/scenario/scenario.cc
// BuildTags lays them out: 1 the goal, 2 the robot, 3 .. 2 + fixed_obstacles the fixed obstacles,
// then the movable ones; each tag lies on its object's top with x_T along the object's x
// (roll 180 deg), so the footprint is the tag's ground position and yaw with the field's sizes.
#include <Eigen/Geometry>
#include <map>

#include "planning/ground_mission/ground_mission_scene.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_params.h"

namespace aperture::experiments {

// The yaw about z_W of the object a tag lies on (x_T along the object's x) [rad].
double TagGroundYaw(const Eigen::Isometry3d& T_WT);

// std::invalid_argument naming the id when the goal's or the robot's tag is missing (the map has
// not seen it: fly the mapping pass again); an obstacle without a tag is not in the scene.
planning::GroundMissionScene TagsMissionScene(const sim::TagsSceneParams& field,
                                              const std::map<int, Eigen::Isometry3d>& T_WT_by_id);

// The true T_WT of every tag object ("tag<id>") of a built `tags` scenario.
std::map<int, Eigen::Isometry3d> TagsScenarioTagPoses(const sim::Scenario& scenario);

}  // namespace aperture::experiments
