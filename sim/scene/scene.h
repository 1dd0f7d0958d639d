#pragma once
// The simulator's world: named objects (primitive + material + pose T_WO), a sky and the light.
// Object ids are assigned by AddObject (1, 2, ...; 0 means sky in the renderer's id mask) and
// stay valid for the scene's life. Poses are settable at any time (moving objects); the renderer
// reads them when a frame is rendered. W: z up.
//
// Build a scene:
//   Scene scene;
//   scene.AddObject({"ground", GroundPlane{}, {grass, Rgb::Ones(), 1.0}, Eigen::Isometry3d::Identity()});
//   const int wall = scene.AddObject({"gap", Rectangle{{2.0, 1.5}, {hole}}, {noise}, T_WG});
//   scene.SetPose("gap", T_WG_new);
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/scene/primitives.h"
#include "sim/scene/textures.h"

namespace aperture::sim {

struct Material {
  std::shared_ptr<const Texture> texture;  // null: plain colour
  Rgb color = Rgb::Constant(0.7f);         // albedo, multiplies the texture
  // The texture is sampled at (uv_m + texture_offset_m) / texture_scale: scale 2 doubles the
  // texture's physical size on the surface.
  double texture_scale = 1.0;
  Eigen::Vector2d texture_offset_m = Eigen::Vector2d::Zero();

  // footprint_m: surface size one sample covers [m] (texture mip level selection).
  Rgb Albedo(const Eigen::Vector2d& uv_m, double footprint_m = 0.0) const {
    if (!texture) return color;
    const double inv_scale = texture_scale == 1.0 ? 1.0 : 1.0 / texture_scale;
    const Eigen::Vector2d st = (uv_m + texture_offset_m) * inv_scale;
    return color.cwiseProduct(texture->Sample(st.x(), st.y(), footprint_m * inv_scale));
  }
};

struct SceneObject {
  SceneObject() = default;
  SceneObject(std::string name_, Primitive primitive_, Material material_ = {},
              const Eigen::Isometry3d& T_WO_ = Eigen::Isometry3d::Identity())
      : name(std::move(name_)), primitive(std::move(primitive_)),
        material(std::move(material_)), T_WO(T_WO_) {}

  std::string name;  // e.g. "gap", "led_target", "tag3"; unique within a scene
  Primitive primitive;
  Material material;
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  int id = 0;  // set by Scene::AddObject
};

// Background radiance by viewing direction d_W: horizon colour at d_W.z = 0 blending linearly in
// d_W.z to zenith colour straight up; below the horizon ground_color (seen where no ground
// object exists).
struct Sky {
  Rgb zenith_color = Rgb(0.45f, 0.6f, 0.9f);
  Rgb horizon_color = Rgb(0.8f, 0.85f, 0.9f);
  Rgb ground_color = Rgb(0.3f, 0.28f, 0.25f);

  Rgb Radiance(const Eigen::Vector3d& d_W) const {
    const double z = d_W.z() / d_W.norm();
    if (z < 0.0) return ground_color;
    return horizon_color + (zenith_color - horizon_color) * static_cast<float>(z);
  }
};

// Lambertian shading: radiance = albedo * (ambient + directional * max(0, n . -direction_W)).
struct Lighting {
  float ambient = 0.35f;
  float directional = 0.65f;
  // Direction the light travels (unit in W): from above, slightly from the side.
  Eigen::Vector3d direction_W = Eigen::Vector3d(0.3, 0.2, -1.0).normalized();
};

// Nearest ray hit in the world.
struct Hit {
  double t_m = 0.0;  // distance along the unit ray [m]
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d n_W = Eigen::Vector3d::Zero();  // unit normal, facing the ray origin
  Eigen::Vector2d uv_m = Eigen::Vector2d::Zero();
  int object_id = 0;
};

class Scene {
 public:
  // Adds the object, assigns and returns its id. Throws std::invalid_argument when the name is
  // empty or already used, or the primitive is invalid (ValidatePrimitive).
  int AddObject(SceneObject object);

  // Lookups; throw std::invalid_argument naming the unknown name or id.
  const SceneObject& object(int id) const;
  const SceneObject& object(const std::string& name) const;
  int FindId(const std::string& name) const;  // -1 when absent

  void SetPose(int id, const Eigen::Isometry3d& T_WO);
  void SetPose(const std::string& name, const Eigen::Isometry3d& T_WO);
  // Mutable material access (e.g. switch a texture between frames).
  Material& material(int id);

  const std::vector<SceneObject>& objects() const { return objects_; }

  // Nearest hit of the ray o_W + t d_W, t in (t_min, t_max) (d_W is normalized here); LEDs are
  // not hit. std::nullopt when the ray reaches the sky.
  std::optional<Hit> Intersect(const Eigen::Vector3d& o_W, const Eigen::Vector3d& d_W,
                               double t_min = 0.0,
                               double t_max = std::numeric_limits<double>::infinity()) const;
  // The same, passing through the objects whose ids are in excluded_ids (e.g. parts of the
  // vehicle a sensor on it looks through).
  std::optional<Hit> Intersect(const Eigen::Vector3d& o_W, const Eigen::Vector3d& d_W,
                               double t_min, double t_max,
                               const std::vector<int>& excluded_ids) const;

  Sky sky;
  Lighting lighting;

 private:
  size_t IndexOf(int id) const;

  std::vector<SceneObject> objects_;  // objects_[i].id == i + 1
};

}  // namespace aperture::sim
