#include "experiments/tags/tags_mission_scene.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace aperture::experiments {
namespace {

planning::GroundBox Footprint(const Eigen::Isometry3d& T_WT, const Eigen::Vector3d& size_m) {
  return {T_WT.translation().head<2>(), size_m.head<2>(), TagGroundYaw(T_WT)};
}

const Eigen::Isometry3d& RequireTag(const std::map<int, Eigen::Isometry3d>& T_WT_by_id, int id,
                                    const char* what) {
  const auto found = T_WT_by_id.find(id);
  if (found == T_WT_by_id.end()) {
    throw std::invalid_argument(std::string("tags mission scene: no pose of tag ") +
                                std::to_string(id) + " (the " + what +
                                "); map the field until it is seen");
  }
  return found->second;
}

}  // namespace

double TagGroundYaw(const Eigen::Isometry3d& T_WT) {
  const Eigen::Matrix3d R_WT = T_WT.rotation();
  return std::atan2(R_WT(1, 0), R_WT(0, 0));
}

planning::GroundMissionScene TagsMissionScene(const sim::TagsSceneParams& field,
                                              const std::map<int, Eigen::Isometry3d>& T_WT_by_id) {
  planning::GroundMissionScene scene;
  scene.area_min_W = Eigen::Vector2d::Zero();
  scene.area_max_W = field.area_m;
  scene.goal_p_W = RequireTag(T_WT_by_id, 1, "goal").translation().head<2>();
  const planning::GroundBox robot =
      Footprint(RequireTag(T_WT_by_id, 2, "robot"), field.robot_size_m);
  scene.robot_p_W = robot.p_W;
  scene.robot_yaw_rad = robot.yaw_rad;
  const int first_movable = 3 + field.fixed_obstacles;
  for (const auto& [id, T_WT] : T_WT_by_id) {
    if (id >= 3 && id < first_movable) {
      scene.fixed_obstacles.push_back(Footprint(T_WT, field.fixed_size_m));
    } else if (id >= first_movable && id < first_movable + field.movable_obstacles) {
      scene.movable_obstacles.push_back(Footprint(T_WT, field.movable_size_m));
    }
  }
  return scene;
}

std::map<int, Eigen::Isometry3d> TagsScenarioTagPoses(const sim::Scenario& scenario) {
  std::map<int, Eigen::Isometry3d> poses;
  const sim::TagsSceneParams& field = scenario.params().tags;
  const int tags = 3 + field.fixed_obstacles + field.movable_obstacles;
  for (int id = 0; id < tags; ++id) {
    const std::string name = "tag" + std::to_string(id);
    if (scenario.scene().FindId(name) >= 0) poses[id] = scenario.scene().object(name).T_WO;
  }
  return poses;
}

}  // namespace aperture::experiments
