#include "sim/scenario/scenario.h"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "control/constants.h"
#include "perception/camera/camera_factory.h"
#include "perception/camera/optical_axes.h"
#include "sim/scene/apriltag_object.h"
#include "sim/scene/counter_hash.h"
#include "sim/scene/gap_pattern_object.h"

namespace aperture::sim {
namespace {

using control::kDegToRad;
// Tags float this far above the surface they lie on so the surface never wins the depth test.
constexpr double kTagLift_m = 0.001;

// Independent random streams (one per purpose) so adding e.g. a tree does not change textures.
enum Stream : std::uint64_t {
  kTextureStream = 1,
  kPlacementStream,
  kJitterStream,
  kLightStream,
  kNoiseStream,
  kShapeStream
};

class SeededRandom {
 public:
  SeededRandom(std::uint64_t seed, Stream stream) : seed_(seed), stream_(stream) {}
  double Uniform(double lo = 0.0, double hi = 1.0) {
    return lo + (hi - lo) * UniformFromHash(HashCounters(seed_, stream_, counter_++));
  }
  double Normal() { return NormalFromHash(HashCounters(seed_, stream_, counter_++)); }
  std::uint64_t Bits() { return HashCounters(seed_, stream_, counter_++); }

 private:
  std::uint64_t seed_;
  std::uint64_t stream_;
  std::uint64_t counter_ = 0;
};

Eigen::Isometry3d MakePose(const Eigen::Vector3d& p_m, const Eigen::Vector3d& rpy_deg) {
  return PoseParams{p_m, rpy_deg}.ToIsometry();
}

// Rectangle standing in a plane x_W = const, facing a viewer looking along +x_W (texture
// unmirrored from that side).
Eigen::Matrix3d FacingPlusX() { return perception::OpticalAxesAlongX(); }

Eigen::Isometry3d Facing(const Eigen::Matrix3d& R_WO, const Eigen::Vector3d& p_W) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R_WO;
  T.translation() = p_W;
  return T;
}

class Builder {
 public:
  Builder(const ScenarioParams& params, Scenario* scenario)
      : params_(params), scene_(scenario->scene()) {}

  std::shared_ptr<const Texture> MakeTexture(const TextureParams& texture) {
    ProceduralTextureParams procedural;
    procedural.texel_size_m = texture.texel_size_m;
    procedural.seed = textures_.Bits();
    if (texture.kind == "none") return nullptr;
    if (texture.kind == "checker") {
      return std::make_shared<Texture>(Texture::Checkerboard(texture.square_size_m));
    }
    if (texture.kind == "noise") return MakeValueNoiseTexture(procedural);
    if (texture.kind == "newspaper") return MakeNewspaperTexture(procedural);
    if (texture.kind == "bark") return MakeBarkTexture(procedural);
    return MakeGrassTexture(procedural);
  }

  Material MakeMaterial(const TextureParams& texture) {
    Material material;
    material.texture = MakeTexture(texture);
    material.color = texture.color.cast<float>();
    material.texture_scale = texture.scale;
    return material;
  }

  Material Textured(const std::string& kind,
                    const Eigen::Vector3d& color = Eigen::Vector3d::Ones()) {
    TextureParams texture;
    texture.kind = kind;
    texture.color = color;
    return MakeMaterial(texture);
  }

  // Seeded pose perturbation of a movable object (randomize.*); identity when all sigmas are 0.
  Eigen::Isometry3d Jitter(const Eigen::Isometry3d& T_WO) {
    const RandomizationParams& r = params_.randomize;
    Eigen::Isometry3d T = T_WO;
    const Eigen::Vector3d dp(jitter_.Normal(), jitter_.Normal(), jitter_.Normal());
    const double dyaw = jitter_.Normal() * r.yaw_sigma_deg * kDegToRad;
    T.translation() += dp * r.position_sigma_m;
    T.linear() = Eigen::AngleAxisd(dyaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * T.linear();
    return T;
  }

  int Add(SceneObject object) { return scene_.AddObject(std::move(object)); }

  void BuildGap() {
    const GapParams& gap = params_.gap;
    const Eigen::Matrix3d R_WG =
        (Eigen::AngleAxisd(gap.yaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(gap.pitch_deg * kDegToRad, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(gap.roll_deg * kDegToRad, Eigen::Vector3d::UnitX()))
            .toRotationMatrix() *
        FacingPlusX();
    Add(MakeGapPatternObject(gap.Pattern(), gap.panel_m, Jitter(Facing(R_WG, gap.center_W))));

    // Textured room around it: x from -3 m, centred in y, floor at z = 0.
    const Eigen::Vector3d room = gap.room_m;
    const double x0 = -3.0, x1 = x0 + room.x(), cx = 0.5 * (x0 + x1);
    Add({"floor", GroundPlane{}, Textured("noise", {0.8, 0.7, 0.6}),
         Eigen::Isometry3d::Identity()});
    Add({"wall_far", Rectangle{{room.y(), room.z()}, {}, {}}, Textured("newspaper"),
         Facing(FacingPlusX(), {x1, 0.0, room.z() / 2})});
    Add({"wall_near", Rectangle{{room.y(), room.z()}, {}, {}}, Textured("noise"),
         Facing(FacingPlusX(), {x0, 0.0, room.z() / 2})});
    Eigen::Matrix3d R_side;  // x_O = x_W, y_O = -z_W, z_O = y_W
    R_side << 1, 0, 0, 0, 0, 1, 0, -1, 0;
    Add({"wall_left", Rectangle{{room.x(), room.z()}, {}, {}},
         Textured("newspaper", {0.9, 0.9, 0.8}), Facing(R_side, {cx, room.y() / 2, room.z() / 2})});
    Add({"wall_right", Rectangle{{room.x(), room.z()}, {}, {}}, Textured("noise", {0.7, 0.8, 0.9}),
         Facing(R_side, {cx, -room.y() / 2, room.z() / 2})});
    Add({"ceiling", Rectangle{{room.x(), room.y()}, {}, {}}, Textured("none", {0.9, 0.9, 0.9}),
         MakePose({cx, 0.0, room.z()}, {180, 0, 0})});
  }

  // The opening's polygon in (x_G right, y_G down) about its centre (GapFlytParams lists the
  // kinds); not used for the ellipse.
  std::vector<Eigen::Vector2d> GapFlytPolygon() {
    const GapFlytParams& g = params_.gapflyt;
    if (!g.vertices_m.empty()) return g.vertices_m;
    const Eigen::Vector2d half = g.size_m / 2.0;
    if (g.shape == "triangle") {
      return {{0.0, -half.y()}, {half.x(), half.y()}, {-half.x(), half.y()}};
    }
    if (g.shape == "notched") {
      const double notch_tip_y = -half.y() + g.notch_depth_ratio * g.size_m.y();
      return {{-half.x(), -half.y()},    {-half.x() / 2, -half.y()}, {0.0, notch_tip_y},
              {half.x() / 2, -half.y()}, {half.x(), -half.y()},      {half.x(), half.y()},
              {-half.x(), half.y()}};
    }
    std::vector<Eigen::Vector2d> vertices;
    if (g.shape == "star") {
      for (int i = 0; i < 2 * g.star_points; ++i) {
        const double angle = -M_PI / 2 + M_PI * i / g.star_points;
        const double r = i % 2 == 0 ? 1.0 : g.star_inner_ratio;
        vertices.emplace_back(r * half.x() * std::cos(angle), r * half.y() * std::sin(angle));
      }
      return vertices;
    }
    // polygon: seeded irregular quadrilateral, corners near 45 + 90 k deg, radii 75..100 % of the
    // box.
    for (int k = 0; k < 4; ++k) {
      const double angle = (45.0 + 90.0 * k + shapes_.Uniform(-15.0, 15.0)) * kDegToRad;
      const double r = shapes_.Uniform(0.75, 1.0);
      const Eigen::Vector2d unit(std::cos(angle), std::sin(angle));
      // Scale to the box: the corner direction's larger component touches the boundary at r = 1.
      const double reach = 1.0 / std::max(std::abs(unit.x()), std::abs(unit.y()));
      vertices.emplace_back(r * reach * unit.x() * half.x(), r * reach * unit.y() * half.y());
    }
    return vertices;
  }

  void BuildGapFlyt() {
    const GapFlytParams& g = params_.gapflyt;
    Rectangle foreground{g.foreground_wall_m, {}, {}};
    if (g.shape == "ellipse") {
      foreground.ellipse_holes.push_back({Eigen::Vector2d::Zero(), g.size_m / 2.0, 0.0});
    } else {
      foreground.polygon_holes.push_back(GapFlytPolygon());
    }
    // The wall's origin is the opening centre ("gap" pose = opening pose).
    Add({"gap", foreground, Textured("newspaper"),
         Jitter(Facing(FacingPlusX(), {g.foreground_x_m, g.center_m.x(), g.center_m.y()}))});
    Add({"background", Rectangle{g.background_wall_m, {}, {}}, Textured("noise", {0.9, 0.8, 0.7}),
         Facing(FacingPlusX(), {g.background_x_m, 0.0, g.background_wall_m.y() / 2})});
    Add({"ground", GroundPlane{}, Textured("grass"), Eigen::Isometry3d::Identity()});
  }

  void BuildLed(Scenario* scenario) {
    const LedSceneParams& led = params_.led;
    Add({"ground", GroundPlane{}, Textured("noise", {0.5, 0.5, 0.5}),
         Eigen::Isometry3d::Identity()});
    const auto attach = [&](SceneObject object) {
      const Eigen::Isometry3d T_BO = object.T_WO;
      object.T_WO = T_WB_start_ * T_BO;
      scenario->AttachToBody(Add(std::move(object)), T_BO);
    };
    // Quadrotor body (T_WO = T_WB) with two crossed arms; LEDs hang below the arms.
    attach({"led_target", Box{{0.14, 0.14, 0.05}}, Textured("none", {0.2, 0.2, 0.2}),
            Eigen::Isometry3d::Identity()});
    attach({"arm1", Box{{0.46, 0.02, 0.01}}, Textured("none", {0.3, 0.3, 0.3}),
            MakePose({0, 0, 0}, {0, 0, 45})});
    attach({"arm2", Box{{0.46, 0.02, 0.01}}, Textured("none", {0.3, 0.3, 0.3}),
            MakePose({0, 0, 0}, {0, 0, -45})});
    for (size_t i = 0; i < led.leds_B.size(); ++i) {
      Eigen::Isometry3d T_BL = Eigen::Isometry3d::Identity();
      T_BL.translation() = led.leds_B[i];
      attach({"led" + std::to_string(i),
              Led{led.led_radius_m, led.led_intensity, Rgb::Ones()},
              {},
              T_BL});
    }
    for (int k = 0; k < led.false_spots; ++k) {
      const Eigen::Vector3d p(placement_.Uniform(-0.5, 0.5) * led.false_spot_area_m.x(),
                              placement_.Uniform(-0.5, 0.5) * led.false_spot_area_m.y(),
                              led.false_spot_height_m);
      Add({"false_spot" + std::to_string(k),
           Led{0.02, 4.0 * led.led_intensity, Rgb::Ones()},
           {},
           MakePose(p, Eigen::Vector3d::Zero())});
    }
  }

  // A seeded spot for a footprint of bounding radius `radius` inside the tag area whose circle
  // clears every taken circle (so footprints never overlap, whatever their yaw).
  Eigen::Vector2d FreeSpot(const Eigen::Vector2d& area, double radius,
                           std::vector<std::pair<Eigen::Vector2d, double>>* taken) {
    constexpr double kGap = 0.05;  // [m] between footprint circles
    for (int attempt = 0; attempt < 1000 && 2.0 * radius < area.minCoeff(); ++attempt) {
      const Eigen::Vector2d p(placement_.Uniform(radius, area.x() - radius),
                              placement_.Uniform(radius, area.y() - radius));
      bool free = true;
      for (const auto& [q, r] : *taken) free = free && (p - q).norm() >= radius + r + kGap;
      if (free) {
        taken->emplace_back(p, radius);
        return p;
      }
    }
    throw std::invalid_argument("tags: no free spot left for object " +
                                std::to_string(taken->size()) + " in area_m [" +
                                std::to_string(area.x()) + ", " + std::to_string(area.y()) +
                                "]; reduce tags.fixed_obstacles / tags.movable_obstacles or "
                                "their sizes");
  }

  // Tag `id` of edge tag_size_m lying on the top face of the box (size, T_WO at its centre),
  // centred, x_Tag along x_O, z_Tag pointing down into the box (seen by a downward camera).
  void AddTopTag(const std::string& owner, const Eigen::Vector3d& size,
                 const Eigen::Isometry3d& T_WO, int id, double tag_size_m) {
    const std::string& family = params_.tags.family;
    const double pattern_m = AprilTagPatternSize(family, tag_size_m);
    if (pattern_m > size.head<2>().minCoeff()) {
      throw std::invalid_argument("tags: the tag of '" + owner + "' (" + std::to_string(pattern_m) +
                                  " m pattern for " + std::to_string(tag_size_m) + " m " + family +
                                  ") does not fit on its " + std::to_string(size.x()) + " x " +
                                  std::to_string(size.y()) +
                                  " m top; use a smaller tag size or a larger object");
    }
    Add(MakeAprilTagObject(family, id, tag_size_m,
                           T_WO * MakePose({0, 0, size.z() / 2 + kTagLift_m}, {180, 0, 0})));
  }

  void BuildTags() {
    const TagsSceneParams& t = params_.tags;
    Add({"ground", GroundPlane{}, Textured("noise", {0.5, 0.5, 0.5}),
         Eigen::Isometry3d::Identity()});
    // The origin tag lies on the ground (z_O = -z_W, x_O = x_W): the map origin.
    Add(MakeAprilTagObject(t.family, 0, t.tag_size_m,
                           MakePose({0.0, 0.0, kTagLift_m}, {180, 0, 0})));
    const double origin_radius = AprilTagPatternSize(t.family, t.tag_size_m) / std::sqrt(2.0);
    std::vector<std::pair<Eigen::Vector2d, double>> taken{{Eigen::Vector2d::Zero(), origin_radius}};
    // Goal: a flat victim mat (red) carrying tag 1.
    const Eigen::Isometry3d T_W_goal = MakePose(
        {t.goal_xy_m.x(), t.goal_xy_m.y(), t.goal_size_m.z() / 2}, Eigen::Vector3d::Zero());
    Add({"goal", Box{t.goal_size_m}, Textured("none", {0.8, 0.15, 0.1}), T_W_goal});
    AddTopTag("goal", t.goal_size_m, T_W_goal, 1, t.tag_size_m);
    taken.emplace_back(t.goal_xy_m, t.goal_size_m.head<2>().norm() / 2);
    const auto tagged_box = [&](const std::string& name, const Eigen::Vector3d& size,
                                const Eigen::Vector3d& color, int id, double tag_size_m) {
      const Eigen::Vector2d xy = FreeSpot(t.area_m, size.head<2>().norm() / 2, &taken);
      const double yaw = placement_.Uniform(-180.0, 180.0);
      // Not jittered: the placement is already seeded, and jitter could make footprints overlap.
      const Eigen::Isometry3d T_WO = MakePose({xy.x(), xy.y(), size.z() / 2}, {0, 0, yaw});
      Add({name, Box{size}, Textured("none", color), T_WO});
      AddTopTag(name, size, T_WO, id, tag_size_m);
    };
    tagged_box("robot", t.robot_size_m, {0.9, 0.55, 0.1}, 2, t.tag_size_m);  // youBot orange
    for (int k = 0; k < t.fixed_obstacles; ++k) {  // grey concrete-like blocks
      tagged_box("fixed" + std::to_string(k), t.fixed_size_m, {0.45, 0.45, 0.5}, 3 + k,
                 t.tag_size_m);
    }
    for (int k = 0; k < t.movable_obstacles; ++k) {  // light blue cubes the gripper lifts
      tagged_box("movable" + std::to_string(k), t.movable_size_m, {0.2, 0.45, 0.85},
                 3 + t.fixed_obstacles + k, t.movable_tag_size_m);
    }
  }

  void BuildForest() {
    const ForestParams& f = params_.forest;
    Add({"ground", GroundPlane{}, Textured("grass"), Eigen::Isometry3d::Identity()});
    std::vector<std::shared_ptr<const Texture>> barks;
    for (int i = 0; i < 3; ++i) barks.push_back(MakeTexture({"bark", {1, 1, 1}, 1.0, 0.005, 0.2}));
    // Placed obstacles as vertical cylinders (centre, radius); boxes by their circumscribed one.
    std::vector<std::pair<Eigen::Vector2d, double>> placed;
    const Eigen::Vector2d start = T_WB_start_.translation().head<2>();
    const Eigen::Vector2d goal = f.goal_m.head<2>();
    const auto place = [&](double radius) -> std::optional<Eigen::Vector2d> {
      for (int attempt = 0; attempt < 200; ++attempt) {
        const Eigen::Vector2d p(2.0 + placement_.Uniform(0.0, f.area_m.x()),
                                placement_.Uniform(-0.5, 0.5) * f.area_m.y());
        bool free = (p - start).norm() - radius >= f.keep_out_m &&
                    (p - goal).norm() - radius >= f.keep_out_m;
        for (const auto& [q, r] : placed) free = free && (p - q).norm() - r - radius >= f.min_gap_m;
        if (free) {
          placed.emplace_back(p, radius);
          return p;
        }
      }
      return std::nullopt;  // area full: fewer objects rather than a blocked one
    };
    for (int k = 0; k < f.trees; ++k) {
      const double radius = placement_.Uniform(f.radius_range_m.x(), f.radius_range_m.y());
      const double height = placement_.Uniform(f.height_range_m.x(), f.height_range_m.y());
      const auto p = place(radius);
      if (!p) break;
      Material bark;
      bark.texture = barks[static_cast<size_t>(k) % barks.size()];
      bark.color = Rgb::Ones();
      bark.texture_offset_m = Eigen::Vector2d(placement_.Uniform(0, 2), placement_.Uniform(0, 2));
      Add({"tree" + std::to_string(k), Cylinder{radius, height}, bark,
           Jitter(MakePose({p->x(), p->y(), 0.0}, Eigen::Vector3d::Zero()))});
    }
    for (int k = 0; k < f.boxes; ++k) {
      const double size = placement_.Uniform(0.4, 1.2);
      const auto p = place(size * std::sqrt(0.5));
      if (!p) break;
      Add({"box" + std::to_string(k), Box{Eigen::Vector3d::Constant(size)},
           Textured("noise", {0.7, 0.6, 0.5}),
           Jitter(MakePose({p->x(), p->y(), size / 2}, {0, 0, placement_.Uniform(0, 90)}))});
    }
  }

  void BuildObjects(Scenario* scenario) {
    for (const auto& [name, o] : params_.objects) {
      Primitive primitive;
      if (o.shape == "rectangle") {
        primitive = Rectangle{o.size_m.head<2>(), o.polygon_holes, o.ellipse_holes};
      } else if (o.shape == "box") {
        primitive = Box{o.size_m};
      } else if (o.shape == "cylinder") {
        primitive = Cylinder{o.radius_m, o.height_m};
      } else if (o.shape == "sphere") {
        primitive = Sphere{o.radius_m};
      } else if (o.shape == "ground") {
        primitive = GroundPlane{};
      } else {
        primitive = Led{o.radius_m, o.intensity, Rgb::Ones()};
      }
      const Eigen::Isometry3d T = o.pose.ToIsometry();
      SceneObject object{name, primitive, MakeMaterial(o.texture), T};
      try {
        if (o.attach_to_body) {
          object.T_WO = T_WB_start_ * T;
          scenario->AttachToBody(Add(std::move(object)), T);
        } else {
          if (o.randomize_pose) object.T_WO = Jitter(T);
          Add(std::move(object));
        }
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("objects." + name + ": " + e.what());
      }
    }
  }

  void SetLighting() {
    const LightingParams& l = params_.lighting;
    const double sigma = params_.randomize.light_sigma;
    Lighting& lighting = scene_.lighting;
    lighting.ambient =
        static_cast<float>(std::max(0.0, l.ambient * (1.0 + sigma * lights_.Normal())));
    lighting.directional =
        static_cast<float>(std::max(0.0, l.directional * (1.0 + sigma * lights_.Normal())));
    const Eigen::Vector3d d = l.direction_W.normalized();
    const Eigen::Vector3d jitter(lights_.Normal(), lights_.Normal(), lights_.Normal());
    lighting.direction_W = (d + sigma * jitter).normalized();
  }

  Eigen::Isometry3d T_WB_start_ = Eigen::Isometry3d::Identity();

 private:
  const ScenarioParams& params_;
  Scene& scene_;
  SeededRandom textures_{params_.seed, kTextureStream};
  SeededRandom placement_{params_.seed, kPlacementStream};
  SeededRandom jitter_{params_.seed, kJitterStream};
  SeededRandom lights_{params_.seed, kLightStream};
  SeededRandom shapes_{params_.seed, kShapeStream};
};

ScenarioCamera BuildCamera(const std::string& name, const CameraParams& c, std::uint64_t seed,
                           std::uint64_t index) {
  Eigen::VectorXd intrinsics = c.intrinsics;
  if (intrinsics.size() == 0) {
    const double half_fov = 0.5 * c.fov_deg * kDegToRad;
    const double f =
        c.model == "equidistant" ? 0.5 * c.width / half_fov : 0.5 * c.width / std::tan(half_fov);
    intrinsics = Eigen::Vector4d(f, f, 0.5 * (c.width - 1), 0.5 * (c.height - 1));
  }
  Eigen::VectorXd distortion = c.distortion;
  if (distortion.size() == 0 && c.model != "pinhole") distortion = Eigen::VectorXd::Zero(4);
  ScenarioCamera camera;
  camera.name = name;
  try {
    camera.model =
        perception::CreateCameraModel(c.model, c.width, c.height, intrinsics, distortion);
    CameraEffectsParams effects;
    effects.gain = c.gain;
    effects.full_well_electrons = c.full_well_electrons;
    effects.read_noise_sigma = c.read_noise_sigma;
    effects.seed = HashCounters(seed, kNoiseStream, index);
    effects.exposure_s = c.exposure_s;
    effects.motion_blur_subframes = c.motion_blur_subframes;
    effects.infrared = c.infrared;
    camera.effects = CameraEffects(effects);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("cameras." + name + ": " + e.what());
  }
  camera.T_BC.reset();
  (c.mount_on_body ? camera.T_BC : camera.T_WC_fixed) = c.pose.ToIsometry();
  camera.rate_hz = c.rate_hz;
  camera.latency_s = c.latency_s;
  camera.drop_probability = c.drop_probability;
  camera.render.color = c.color;
  camera.render.supersampling = c.supersampling;
  return camera;
}

}  // namespace

const ScenarioCamera& Scenario::camera(const std::string& name) const {
  std::string known;
  for (const ScenarioCamera& camera : cameras_) {
    if (camera.name == name) return camera;
    known += (known.empty() ? "" : ", ") + camera.name;
  }
  throw std::invalid_argument("scenario '" + kind() + "' has no camera '" + name +
                              "'; cameras: " + known);
}

const ScenarioCamera& Scenario::render_camera() const {
  return params_.trajectory.camera.empty() ? cameras_.front() : camera(params_.trajectory.camera);
}

void Scenario::AttachToBody(int object_id, const Eigen::Isometry3d& T_BO) {
  scene_.object(object_id);  // throws for an unknown id
  attached_.push_back({object_id, T_BO});
}

void Scenario::SetVehiclePose(const Eigen::Isometry3d& T_WB) {
  for (const Attached& a : attached_) scene_.SetPose(a.object_id, T_WB * a.T_BO);
}

std::vector<std::string> Scenario::AttachedObjectNames() const {
  std::vector<std::string> names;
  for (const Attached& a : attached_) names.push_back(scene_.object(a.object_id).name);
  return names;
}

Scenario BuildScenario(const ScenarioParams& params) {
  Scenario scenario;
  scenario.params_ = params;
  scenario.T_WB_start_ = params.vehicle_start.ToIsometry();
  Builder builder(scenario.params_, &scenario);
  builder.T_WB_start_ = scenario.T_WB_start_;
  builder.SetLighting();
  if (params.scenario == "gap") builder.BuildGap();
  if (params.scenario == "gapflyt") builder.BuildGapFlyt();
  if (params.scenario == "led") builder.BuildLed(&scenario);
  if (params.scenario == "tags") builder.BuildTags();
  if (params.scenario == "forest") builder.BuildForest();
  builder.BuildObjects(&scenario);
  if (params.cameras.empty()) {
    throw std::invalid_argument("scenario '" + params.scenario + "' has no cameras");
  }
  for (size_t i = 0; i < params.cameras.size(); ++i) {
    scenario.cameras_.push_back(
        BuildCamera(params.cameras[i].first, params.cameras[i].second, params.seed, i));
  }
  return scenario;
}

}  // namespace aperture::sim
