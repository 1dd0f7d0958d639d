#include "sim/scene/scene.h"

#include <algorithm>
#include <stdexcept>

namespace aperture::sim {

int Scene::AddObject(SceneObject object) {
  if (object.name.empty()) {
    throw std::invalid_argument("Scene::AddObject: object name is empty; give every object a name");
  }
  if (FindId(object.name) >= 0) {
    throw std::invalid_argument("Scene::AddObject: object name '" + object.name +
                                "' already used; names must be unique");
  }
  ValidatePrimitive(object.primitive);
  object.id = static_cast<int>(objects_.size()) + 1;
  objects_.push_back(std::move(object));
  return objects_.back().id;
}

size_t Scene::IndexOf(int id) const {
  if (id < 1 || id > static_cast<int>(objects_.size())) {
    throw std::invalid_argument("Scene: unknown object id " + std::to_string(id) + " (scene has " +
                                std::to_string(objects_.size()) + " objects)");
  }
  return static_cast<size_t>(id - 1);
}

const SceneObject& Scene::object(int id) const { return objects_[IndexOf(id)]; }

const SceneObject& Scene::object(const std::string& name) const {
  const int id = FindId(name);
  if (id < 0) throw std::invalid_argument("Scene: no object named '" + name + "'");
  return objects_[IndexOf(id)];
}

int Scene::FindId(const std::string& name) const {
  for (const SceneObject& o : objects_) {
    if (o.name == name) return o.id;
  }
  return -1;
}

void Scene::SetPose(int id, const Eigen::Isometry3d& T_WO) { objects_[IndexOf(id)].T_WO = T_WO; }

void Scene::SetPose(const std::string& name, const Eigen::Isometry3d& T_WO) {
  const int id = FindId(name);
  if (id < 0) throw std::invalid_argument("Scene::SetPose: no object named '" + name + "'");
  SetPose(id, T_WO);
}

Material& Scene::material(int id) { return objects_[IndexOf(id)].material; }

std::optional<Hit> Scene::Intersect(const Eigen::Vector3d& o_W, const Eigen::Vector3d& d_W,
                                    double t_min, double t_max) const {
  return Intersect(o_W, d_W, t_min, t_max, {});
}

std::optional<Hit> Scene::Intersect(const Eigen::Vector3d& o_W, const Eigen::Vector3d& d_W,
                                    double t_min, double t_max,
                                    const std::vector<int>& excluded_ids) const {
  const Eigen::Vector3d d = d_W.normalized();
  std::optional<Hit> best;
  double best_t = t_max;
  for (const SceneObject& object : objects_) {
    if (std::find(excluded_ids.begin(), excluded_ids.end(), object.id) != excluded_ids.end()) {
      continue;
    }
    const Eigen::Isometry3d T_OW = object.T_WO.inverse();
    LocalHit local;
    if (!IntersectPrimitive(object.primitive, T_OW * o_W, T_OW.linear() * d, t_min, best_t,
                            &local)) {
      continue;
    }
    best_t = local.t_m;
    Hit hit;
    hit.t_m = local.t_m;
    hit.p_W = o_W + local.t_m * d;
    hit.n_W = object.T_WO.linear() * local.n_O;
    if (hit.n_W.dot(d) > 0.0) hit.n_W = -hit.n_W;
    hit.uv_m = local.uv_m;
    hit.object_id = object.id;
    best = hit;
  }
  return best;
}

}  // namespace aperture::sim
