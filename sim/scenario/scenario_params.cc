#include "sim/scenario/scenario_params.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "control/require.h"
#include "perception/led/led_configuration.h"
#include "sim/render/camera_effects.h"
#include "sim/sim_params_io.h"

namespace aperture::sim {
namespace {

// The largest camera image side [px] and supersampling factor a scenario accepts.
constexpr int kMaxCameraSidePx = 8192;
constexpr int kMaxSupersampling = 8;

// The camera effects' own checks (gain, noise, exposure, CameraEffects) at load time, so a bad
// value names its file line or --set item and the camera's key.
struct CameraEffectsCheck {
  CameraEffectsParams effects;
  void Validate() const { CameraEffects checked(effects); }
};

// String choices through ReadEnum so a typo lists the allowed names with its location.
void ReadChoice(config::ParamReader& reader, const std::string& key, std::string* value,
                const std::vector<std::string>& allowed) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& name : allowed) pairs.emplace_back(name, name);
  reader.ReadEnum(key, value, pairs);
}

[[noreturn]] void ThrowAt(const config::ParamReader& reader, const std::string& key,
                          const std::string& what) {
  reader.Fail(key, what);
}

// control::RequirePositive with the key's location ("file:line:col: 'gap.opening_m'") as its name.
void RequirePositiveAt(const config::ParamReader& reader, const std::string& key, double value) {
  try {
    control::RequirePositive(value, reader.FullKey(key));
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();  // "<key> = <value> must be finite and > 0"
    reader.Fail(key, message.substr(message.find("= ")));
  }
}

void RequirePositiveAt(const config::ParamReader& reader, const std::string& key,
                       const Eigen::VectorXd& values) {
  for (Eigen::Index i = 0; i < values.size(); ++i) RequirePositiveAt(reader, key, values[i]);
}

// A SITL block that replaces the caller's part of SitlRunnerParams only when present.
template <typename T>
void ReadOptionalSection(config::ParamReader& reader, const std::string& key,
                         std::optional<T>* value) {
  if (!reader.Has(key)) return;
  T loaded;
  reader.ReadSection(key, &loaded);
  *value = std::move(loaded);
}

}  // namespace

Eigen::Isometry3d PoseParams::ToIsometry() const {
  const Eigen::Vector3d rpy = rpy_deg * (M_PI / 180.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = p_m;
  return T;
}

perception::GapPattern GapParams::Pattern() const {
  perception::GapPattern pattern;
  pattern.opening_size_m = opening_m;
  pattern.inner_size_m = pattern_inner_m;
  pattern.outer_size_m = pattern_outer_m;
  return pattern;
}

void LoadParams(config::ParamReader& reader, PoseParams* params) {
  reader.Read("p_m", &params->p_m);
  reader.Read("rpy_deg", &params->rpy_deg);
}

void LoadParams(config::ParamReader& reader, TextureParams* params) {
  ReadChoice(reader, "kind", &params->kind,
             {"none", "checker", "noise", "newspaper", "bark", "grass"});
  reader.Read("color", &params->color);
  reader.Read("scale", &params->scale);
  reader.Read("texel_size_m", &params->texel_size_m);
  reader.Read("square_size_m", &params->square_size_m);
  RequirePositiveAt(reader, "scale", params->scale);
  RequirePositiveAt(reader, "texel_size_m", params->texel_size_m);
  RequirePositiveAt(reader, "square_size_m", params->square_size_m);
}

void LoadParams(config::ParamReader& reader, ObjectParams* params) {
  ReadChoice(reader, "shape", &params->shape,
             {"rectangle", "box", "cylinder", "sphere", "ground", "led"});
  reader.Read("size_m", &params->size_m);
  reader.Read("radius_m", &params->radius_m);
  reader.Read("height_m", &params->height_m);
  reader.Read("intensity", &params->intensity);
  reader.Read("polygon_holes", &params->polygon_holes);
  std::vector<Eigen::Matrix<double, 5, 1>> ellipse_rows;  // [x, y, semi_x, semi_y, angle_deg]
  reader.Read("ellipse_holes", &ellipse_rows);
  if (!ellipse_rows.empty()) {
    params->ellipse_holes.clear();
    for (const Eigen::Matrix<double, 5, 1>& row : ellipse_rows) {
      params->ellipse_holes.push_back({row.head<2>(), row.segment<2>(2), row[4] * M_PI / 180.0});
    }
  }
  if (params->shape != "rectangle" &&
      (!params->polygon_holes.empty() || !params->ellipse_holes.empty())) {
    ThrowAt(reader, params->polygon_holes.empty() ? "ellipse_holes" : "polygon_holes",
            "is only for shape: rectangle, not '" + params->shape + "'");
  }
  reader.ReadSection("pose", &params->pose);
  reader.Read("attach_to_body", &params->attach_to_body);
  reader.Read("randomize_pose", &params->randomize_pose);
  reader.ReadSection("texture", &params->texture);
}

void LoadParams(config::ParamReader& reader, LightingParams* params) {
  reader.Read("ambient", &params->ambient);
  reader.Read("directional", &params->directional);
  reader.Read("direction_W", &params->direction_W);
  if (params->ambient < 0.0 || params->directional < 0.0) {
    ThrowAt(reader, "ambient", "and 'directional' must be >= 0");
  }
  if (!(params->direction_W.norm() > 0.0)) ThrowAt(reader, "direction_W", "must be non-zero");
}

void LoadParams(config::ParamReader& reader, RandomizationParams* params) {
  reader.Read("position_sigma_m", &params->position_sigma_m);
  reader.Read("yaw_sigma_deg", &params->yaw_sigma_deg);
  reader.Read("light_sigma", &params->light_sigma);
  if (params->position_sigma_m < 0.0 || params->yaw_sigma_deg < 0.0 || params->light_sigma < 0.0) {
    ThrowAt(reader, "position_sigma_m", "and the other sigmas must be >= 0");
  }
}

void LoadParams(config::ParamReader& reader, CameraParams* params) {
  ReadChoice(reader, "model", &params->model, {"pinhole", "radtan", "equidistant"});
  reader.Read("width", &params->width);
  reader.Read("height", &params->height);
  reader.Read("fov_deg", &params->fov_deg);
  reader.Read("intrinsics", &params->intrinsics);
  reader.Read("distortion", &params->distortion);
  reader.Read("mount_on_body", &params->mount_on_body);
  reader.ReadSection("pose", &params->pose);
  reader.Read("rate_hz", &params->rate_hz);
  reader.Read("latency_s", &params->latency_s);
  reader.Read("exposure_s", &params->exposure_s);
  reader.Read("motion_blur_subframes", &params->motion_blur_subframes);
  reader.Read("gain", &params->gain);
  reader.Read("read_noise_sigma", &params->read_noise_sigma);
  reader.Read("full_well_electrons", &params->full_well_electrons);
  reader.Read("color", &params->color);
  reader.Read("infrared", &params->infrared);
  reader.Read("supersampling", &params->supersampling);
  reader.Read("drop_probability", &params->drop_probability);
  // Image sides up to 8K (7680 x 4320) and 8 x 8 rays per pixel: larger frames do not fit the
  // renderer's per-frame buffers in memory.
  for (const auto& [key, value] :
       {std::pair<const char*, int>{"width", params->width}, {"height", params->height}}) {
    if (value < 1 || value > kMaxCameraSidePx) {
      ThrowAt(reader, key,
              "must be in [1, " + std::to_string(kMaxCameraSidePx) + "] pixels, got " +
                  std::to_string(value));
    }
  }
  RequirePositiveAt(reader, "rate_hz", params->rate_hz);
  if (params->supersampling < 1 || params->supersampling > kMaxSupersampling) {
    ThrowAt(reader, "supersampling",
            "must be in [1, " + std::to_string(kMaxSupersampling) +
                "] (rays per pixel side), got " + std::to_string(params->supersampling));
  }
  if (!(params->latency_s >= 0.0) || !std::isfinite(params->latency_s)) {
    ThrowAt(reader, "latency_s",
            "must be finite and >= 0, got " + std::to_string(params->latency_s));
  }
  if (!(params->drop_probability >= 0.0 && params->drop_probability < 1.0)) {
    ThrowAt(reader, "drop_probability",
            "must be in [0, 1), got " + std::to_string(params->drop_probability));
  }
  CameraEffectsCheck effects;
  effects.effects.gain = params->gain;
  effects.effects.full_well_electrons = params->full_well_electrons;
  effects.effects.read_noise_sigma = params->read_noise_sigma;
  effects.effects.exposure_s = params->exposure_s;
  effects.effects.motion_blur_subframes = params->motion_blur_subframes;
  reader.Validate(effects);
  if (params->intrinsics.size() == 0 &&
      (!(params->fov_deg > 0.0) || (params->model != "equidistant" && !(params->fov_deg < 180.0)) ||
       params->fov_deg > 360.0)) {
    ThrowAt(reader, "fov_deg",
            "must be in (0, 180) for pinhole/radtan and (0, 360] for equidistant, got " +
                std::to_string(params->fov_deg));
  }
}

void LoadParams(config::ParamReader& reader, TrajectoryParams* params) {
  ReadChoice(reader, "kind", &params->kind, {"hover", "line", "circle", "scan", "random"});
  reader.Read("camera", &params->camera);
  reader.Read("frames", &params->frames);
  reader.Read("end_p_m", &params->end_p_m);
  reader.Read("center_p_m", &params->center_p_m);
  reader.Read("arc_deg", &params->arc_deg);
  reader.Read("amplitude_m", &params->amplitude_m);
  reader.Read("cycles", &params->cycles);
  reader.Read("angle_amplitude_deg", &params->angle_amplitude_deg);
  RequirePositiveAt(reader, "frames", params->frames);
}

void LoadParams(config::ParamReader& reader, GapParams* params) {
  reader.Read("center_W", &params->center_W);
  reader.Read("roll_deg", &params->roll_deg);
  reader.Read("pitch_deg", &params->pitch_deg);
  reader.Read("yaw_deg", &params->yaw_deg);
  reader.Read("opening_m", &params->opening_m);
  reader.Read("pattern_inner_m", &params->pattern_inner_m);
  reader.Read("pattern_outer_m", &params->pattern_outer_m);
  reader.Read("panel_m", &params->panel_m);
  reader.Read("room_m", &params->room_m);
  RequirePositiveAt(reader, "opening_m", params->opening_m);
  RequirePositiveAt(reader, "room_m", params->room_m);
  const bool nested = (params->pattern_inner_m.array() > params->opening_m.array()).all() &&
                      (params->pattern_outer_m.array() > params->pattern_inner_m.array()).all() &&
                      (params->panel_m.array() > params->pattern_outer_m.array()).all();
  if (!nested) {
    ThrowAt(reader, "pattern_outer_m",
            ": the gap needs opening_m < pattern_inner_m < pattern_outer_m < panel_m in both "
            "dimensions");
  }
}

void LoadParams(config::ParamReader& reader, GapFlytParams* params) {
  reader.Read("foreground_x_m", &params->foreground_x_m);
  reader.Read("background_x_m", &params->background_x_m);
  ReadChoice(reader, "shape", &params->shape,
             {"ellipse", "polygon", "triangle", "notched", "star"});
  reader.Read("center_m", &params->center_m);
  reader.Read("size_m", &params->size_m);
  reader.Read("vertices_m", &params->vertices_m);
  reader.Read("notch_depth_ratio", &params->notch_depth_ratio);
  reader.Read("star_points", &params->star_points);
  reader.Read("star_inner_ratio", &params->star_inner_ratio);
  reader.Read("foreground_wall_m", &params->foreground_wall_m);
  reader.Read("background_wall_m", &params->background_wall_m);
  RequirePositiveAt(reader, "size_m", params->size_m);
  if (!(params->background_x_m > params->foreground_x_m)) {
    ThrowAt(reader, "background_x_m", "must be larger than foreground_x_m");
  }
  if (params->star_points < 3 || !(params->star_inner_ratio > 0.0) ||
      !(params->star_inner_ratio < 1.0)) {
    ThrowAt(reader, "star_points", "must be >= 3 with star_inner_ratio in (0, 1)");
  }
  if (!params->vertices_m.empty() && params->vertices_m.size() < 3) {
    ThrowAt(reader, "vertices_m", "needs at least 3 vertices (or none for the default)");
  }
  if (!params->vertices_m.empty() && params->shape != "polygon") {
    ThrowAt(reader, "vertices_m", "is only for shape: polygon, not '" + params->shape + "'");
  }
  if (!(params->notch_depth_ratio > 0.0) || !(params->notch_depth_ratio < 1.0)) {
    ThrowAt(reader, "notch_depth_ratio",
            "must be in (0, 1), got " + std::to_string(params->notch_depth_ratio));
  }
}

void LoadParams(config::ParamReader& reader, LedSceneParams* params) {
  reader.Read("config", &params->config);
  reader.Read("leds", &params->leds_B);
  reader.Read("led_radius_m", &params->led_radius_m);
  reader.Read("led_intensity", &params->led_intensity);
  reader.Read("false_spots", &params->false_spots);
  reader.Read("false_spot_area_m", &params->false_spot_area_m);
  reader.Read("false_spot_height_m", &params->false_spot_height_m);
  // The target frame T of perception::LedConfiguration is the body frame B here. Its checks (4..8
  // LEDs, spacing, not coplanar, no symmetry) hold for a file and for inline `leds` alike.
  if (!params->config.empty()) {
    params->leds_B = perception::LedConfiguration::Load(params->config).p_T();
  } else {
    perception::LedConfiguration(params->leds_B,
                                 reader.Where("leds") + " '" + reader.FullKey("leds") + "'");
  }
  RequirePositiveAt(reader, "led_radius_m", params->led_radius_m);
  RequirePositiveAt(reader, "led_intensity", params->led_intensity);
  if (params->false_spots < 0) ThrowAt(reader, "false_spots", "must be >= 0");
}

void LoadParams(config::ParamReader& reader, TagsSceneParams* params) {
  reader.Read("area_m", &params->area_m);
  reader.Read("family", &params->family);
  reader.Read("tag_size_m", &params->tag_size_m);
  reader.Read("movable_obstacles", &params->movable_obstacles);
  reader.Read("movable_size_m", &params->movable_size_m);
  reader.Read("movable_tag_size_m", &params->movable_tag_size_m);
  reader.Read("fixed_obstacles", &params->fixed_obstacles);
  reader.Read("fixed_size_m", &params->fixed_size_m);
  reader.Read("robot_size_m", &params->robot_size_m);
  reader.Read("goal_xy_m", &params->goal_xy_m);
  reader.Read("goal_size_m", &params->goal_size_m);
  RequirePositiveAt(reader, "area_m", params->area_m);
  RequirePositiveAt(reader, "tag_size_m", params->tag_size_m);
  RequirePositiveAt(reader, "movable_size_m", params->movable_size_m);
  RequirePositiveAt(reader, "movable_tag_size_m", params->movable_tag_size_m);
  RequirePositiveAt(reader, "fixed_size_m", params->fixed_size_m);
  RequirePositiveAt(reader, "robot_size_m", params->robot_size_m);
  RequirePositiveAt(reader, "goal_size_m", params->goal_size_m);
  if (params->movable_obstacles < 0) ThrowAt(reader, "movable_obstacles", "must be >= 0");
  if (params->fixed_obstacles < 0) ThrowAt(reader, "fixed_obstacles", "must be >= 0");
}

void LoadParams(config::ParamReader& reader, ForestParams* params) {
  reader.Read("trees", &params->trees);
  reader.Read("boxes", &params->boxes);
  reader.Read("area_m", &params->area_m);
  reader.Read("min_gap_m", &params->min_gap_m);
  reader.Read("keep_out_m", &params->keep_out_m);
  reader.Read("radius_range_m", &params->radius_range_m);
  reader.Read("height_range_m", &params->height_range_m);
  reader.Read("goal_m", &params->goal_m);
  RequirePositiveAt(reader, "area_m", params->area_m);
  RequirePositiveAt(reader, "min_gap_m", params->min_gap_m);
  if (!(params->keep_out_m >= 0.0)) ThrowAt(reader, "keep_out_m", "must be >= 0");
  if (!params->goal_m.allFinite()) ThrowAt(reader, "goal_m", "must be finite");
  RequirePositiveAt(reader, "radius_range_m", params->radius_range_m);
  RequirePositiveAt(reader, "height_range_m", params->height_range_m);
  if (params->trees < 0 || params->boxes < 0) ThrowAt(reader, "trees", "and boxes must be >= 0");
}

void LoadParams(config::ParamReader& reader, ScenarioParams* params) {
  ReadChoice(reader, "scenario", &params->scenario,
             {"gap", "gapflyt", "led", "tags", "forest", "empty"});
  reader.Read("seed", &params->seed);
  reader.ReadSection("lighting", &params->lighting);
  reader.ReadSection("randomize", &params->randomize);
  {
    config::ParamReader vehicle = reader.Section("vehicle");
    vehicle.ReadSection("start", &params->vehicle_start);
    vehicle.RejectUnknownKeys();
  }
  {
    // --set cameras.frnt.rate_hz=30 is a typo, not a second camera (that takes a --config file).
    config::ParamReader cameras = reader.Section("cameras");
    cameras.RejectEntriesCreatedBySet("camera");
    params->cameras.clear();
    for (const std::string& name : cameras.Keys()) {
      CameraParams camera;
      cameras.ReadSection(name, &camera);
      params->cameras.emplace_back(name, camera);
    }
    if (params->cameras.empty()) ThrowAt(reader, "cameras", "needs at least one camera");
  }
  reader.ReadSection("trajectory", &params->trajectory);
  // Only the kind's own section: a section of another kind is a mistake worth reporting.
  if (params->scenario == "gap") reader.ReadSection("gap", &params->gap);
  if (params->scenario == "gapflyt") reader.ReadSection("gapflyt", &params->gapflyt);
  if (params->scenario == "led") reader.ReadSection("led", &params->led);
  if (params->scenario == "tags") reader.ReadSection("tags", &params->tags);
  if (params->scenario == "forest") reader.ReadSection("forest", &params->forest);
  {
    // Extra objects are the user's to add, also by --set when it names the shape
    // (objects.crate.shape=box); --set objects.crat.radius_m=1 alone is a typo.
    config::ParamReader objects = reader.Section("objects");
    objects.RejectEntriesCreatedBySet("object", "shape");
    params->objects.clear();
    for (const std::string& name : objects.Keys()) {
      ObjectParams object;
      objects.ReadSection(name, &object);
      params->objects.emplace_back(name, object);
    }
  }
  reader.ReadSection("disturbances", &params->disturbances);
  ReadOptionalSection(reader, "dynamics", &params->dynamics);
  ReadOptionalSection(reader, "imu", &params->imu);
  ReadOptionalSection(reader, "range", &params->range);
  ReadOptionalSection(reader, "collision", &params->collision);
  ReadOptionalSection(reader, "sitl", &params->sitl);
  const auto& trajectory_camera = params->trajectory.camera;
  if (!trajectory_camera.empty()) {
    bool found = false;
    for (const auto& [name, camera] : params->cameras) found = found || name == trajectory_camera;
    if (!found) {
      std::string known;
      for (const auto& [name, camera] : params->cameras)
        known += (known.empty() ? "" : ", ") + name;
      ThrowAt(
          reader.Section("trajectory"), "camera",
          "names camera '" + trajectory_camera + "', which is not in 'cameras'; known: " + known);
    }
  }
}

}  // namespace aperture::sim
