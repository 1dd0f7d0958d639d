#pragma once
// Moves an object of the `tags` scenario together with the tag on its top (scenario.cc
// AddTopTag: a separate object "tag<id>" at a fixed pose on the object's top face), as a ground
// robot drives or carries an obstacle: both poses change, the tag keeps its place on the object.
#include <Eigen/Geometry>
#include <string>

#include "sim/scene/scene.h"

namespace aperture::experiments {

class TaggedObjectMover {
 public:
  // The object `name` and its tag `tag_name` as placed in `scene` now. Throws
  // std::invalid_argument naming what is missing.
  TaggedObjectMover(const sim::Scene& scene, const std::string& name, const std::string& tag_name);

  // Places the object at T_WO (and the tag on it).
  void MoveTo(const Eigen::Isometry3d& T_WO, sim::Scene* scene) const;
  // The object's pose for a ground pose (centre x, y and yaw about z_W) at its resting height.
  Eigen::Isometry3d PoseAt(const Eigen::Vector2d& p_W, double yaw_rad) const;

  const Eigen::Isometry3d& T_WO_start() const { return T_WO_start_; }

 private:
  std::string name_;
  std::string tag_name_;
  Eigen::Isometry3d T_WO_start_;
  Eigen::Isometry3d T_OT_;  // the tag on the object
};

}  // namespace aperture::experiments
