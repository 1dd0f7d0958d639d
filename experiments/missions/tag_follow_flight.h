#pragma once
// Mission `follow` of scenario `tags` (issue 16, items 2-3; paper D Sec. D.6): the ground robot
// executes the time-optimal mission the planner finds on the field (planning/ground_mission/:
// Alg. 2/3, place search; on the scenario's true tag poses — chaining the `map` mission's map
// into the plan is issue 16's item 4) open loop, as planning::GroundMissionTimeline times it
// (driving at robot_speed_mps, turning, grasping, carrying and placing movable obstacles); the
// quadrotor flies planning::TagFollowAutopilot: it searches the field from above, finds the
// robot's tag and servoes on its corners to stay above it. The robot starts once the quadrotor
// has locked on above it (TagFollowParams::lock_error; paper D's robot waits for the quadrotor's
// commands) and not before robot_start_s.
//
// Keys of `mission` (`--set mission.robot_speed_mps=0.3`): robot_start_s, robot_speed_mps, the
// odometry section (odometry_adapter.h), and planning::TagFollowParams's keys
// (planning/tag_follow/tag_follow_autopilot.h).
//
// Rendering of the execution: the robot and its tag move with the timeline; an obstacle in the
// gripper is drawn in front of the robot (the youBot's arm holds it there, not over the robot's
// tag), lifted clear of the ground; placed obstacles lie where the plan put them.
//
// Passed (ground truth): no collision, the robot's whole mission executed within the run, and the
// robot tag's centre within 10 % of the image width of the image centre at every 5 ms sample
// while the robot executes (the acceptance; summary.json "mission": max_offset_of_width,
// median_offset_of_width, ...). Files: objects.csv (t, name and T_WO of the robot and every
// movable obstacle at 10 Hz) and follow.csv (per frame: tag seen, its image centre, the servo
// error and reference).
#include <memory>

#include "experiments/missions/mission_registry.h"

namespace aperture::experiments {

std::unique_ptr<MissionFlight> MakeTagFollowFlight(const MissionContext& context);
// Mission `deliver`, paper D's whole mission: the mapping flight (mission `map`), the map
// optimized, the robot's mission planned on the map's tag poses, then `follow`'s execution.
std::unique_ptr<MissionFlight> MakeTagDeliveryFlight(const MissionContext& context);

}  // namespace aperture::experiments
