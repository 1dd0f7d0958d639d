#include "experiments/tags/tagged_object_mover.h"

#include <stdexcept>

namespace aperture::experiments {

TaggedObjectMover::TaggedObjectMover(const sim::Scene& scene, const std::string& name,
                                     const std::string& tag_name)
    : name_(name), tag_name_(tag_name) {
  for (const std::string& required : {name, tag_name}) {
    if (scene.FindId(required) < 0) {
      throw std::invalid_argument("TaggedObjectMover: the scene has no object '" + required +
                                  "' (scenario 'tags' names them robot, movable<k>, tag<id>)");
    }
  }
  T_WO_start_ = scene.object(name).T_WO;
  T_OT_ = T_WO_start_.inverse() * scene.object(tag_name).T_WO;
}

void TaggedObjectMover::MoveTo(const Eigen::Isometry3d& T_WO, sim::Scene* scene) const {
  scene->SetPose(name_, T_WO);
  scene->SetPose(tag_name_, T_WO * T_OT_);
}

Eigen::Isometry3d TaggedObjectMover::PoseAt(const Eigen::Vector2d& p_W, double yaw_rad) const {
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_WO.translation() = Eigen::Vector3d(p_W.x(), p_W.y(), T_WO_start_.translation().z());
  return T_WO;
}

}  // namespace aperture::experiments
