#pragma once
// The ground robot's mission seen from above, as an inset in the lower left corner of the onboard
// video (missions `follow` and `deliver`): the field, the fixed obstacles as the mission was
// planned on them (map or truth), the planned path (green), the goal's mat and, where they truly
// are now, the movable obstacles (orange) and the robot (red outline, its front marked).
#include <opencv2/core/mat.hpp>

#include "planning/ground_mission/ground_mission_timeline.h"

namespace aperture::experiments {

struct GroundMissionInsetSizes {
  Eigen::Vector2d goal_m = Eigen::Vector2d(0.6, 0.6);
  Eigen::Vector2d robot_m = Eigen::Vector2d(0.58, 0.38);
  Eigen::Vector2d movable_m = Eigen::Vector2d(0.18, 0.18);
};

// Draws into *bgr (CV_8UC3) at a third of its height; `truth` is the robot and obstacles now.
void DrawGroundMissionInset(const planning::GroundMissionScene& scene,
                            const planning::GroundMissionTimeline& timeline,
                            const planning::GroundRobotSample& truth,
                            const GroundMissionInsetSizes& sizes, cv::Mat* bgr);

}  // namespace aperture::experiments
