#pragma once
// Parameters of a simulator scenario, loaded from YAML with config::ParamReader (strict: unknown
// keys fail with file:line, key and the known keys). A scenario is one YAML map:
//
//   scenario: gap            # kind: gap | gapflyt | led | tags | forest | empty (objects only)
//   seed: 0                  # drives every random choice: textures, placements, pose jitter,
//                            # lighting jitter, sensor noise. Same seed -> bit-identical frames.
//   lighting: {ambient: 0.35, directional: 0.65, direction_W: [0.3, 0.2, -1]}
//   randomize: {position_sigma_m: 0, yaw_sigma_deg: 0, light_sigma: 0}
//   vehicle: {start: {p_m: [0, 0, 1.5], rpy_deg: [0, 0, 0]}}
//   cameras:                 # name -> camera; render uses trajectory.camera (default: first)
//     front: {model: equidistant, width: 752, height: 480, fov_deg: 180, ...}
//   trajectory: {kind: line, ...}   # kinematic vehicle path for `aperture render`
//   gap: {...}               # the section of the kind (only that one is accepted)
//   objects:                 # extra objects, name -> object
//     crate: {shape: box, size_m: [1, 1, 1], pose: {p_m: [3, 2, 0.5]}, texture: {kind: noise}}
//   disturbances:            # SITL only: gusts and pushes (sim/sim_params_io.h)
//     gusts: [[t_start_s, duration_s, wind_x, wind_y, wind_z]]
//     pushes: [[t_s, J_x, J_y, J_z]]
//   # SITL only, formats in sim/sim_params_io.h; each block present replaces that part of the
//   # caller's SitlRunnerParams (its absent keys: the in-class defaults), absent blocks leave it:
//   dynamics: {vehicle: {mass_kg: 0.45, rotor: {time_constant_up_s: 0.011}}, ...}
//   imu: {rate_hz: 500, accel_noise_density: 3.9e-3, ...}
//   range: {rate_hz: 100, noise_sigma_m: 0.01, ...}
//   collision: {body_radius_m: 0.08, propeller_radius_m: 0.0635, ...}
//   sitl: {dynamics_rate_hz: 1000, control_rate_hz: 100, command_latency_s: 0.01,
//          range_latency_s: 0, range_enabled: true, start_hovering: true}
//   (cameras.<name>.drop_probability: SITL frame drops, see CameraParams.)
//
// Poses: p_m [m] and rpy_deg [deg] with R = Rz(yaw) * Ry(pitch) * Rx(roll) (rpy = [roll, pitch,
// yaw]). World W: z up. Body B: x forward, y left, z up. Camera C: OpenCV (z forward, y down).
// Rectangles (walls, tags, the gap panel) show their texture unmirrored to a viewer looking
// along +z_O (primitives.h).
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config/param_reader.h"
#include "perception/gap/gap_pattern.h"
#include "sim/scene/primitives.h"
#include "sim/sensors/imu_sensor.h"
#include "sim/sensors/range_sensor.h"
#include "sim/sitl/collision_checker.h"
#include "sim/sitl/sitl_runner.h"
#include "sim/vehicle/disturbances.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::sim {

struct PoseParams {
  Eigen::Vector3d p_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy_deg = Eigen::Vector3d::Zero();  // [roll, pitch, yaw]

  Eigen::Isometry3d ToIsometry() const;
};

struct TextureParams {
  // none | checker | noise | newspaper | bark | grass
  std::string kind = "none";
  Eigen::Vector3d color = Eigen::Vector3d::Constant(0.7);  // albedo multiplier (RGB)
  double scale = 1.0;          // physical size factor of the texture on the surface
  double texel_size_m = 0.01;  // procedural textures: 256 texels * 1 cm = 2.56 m period
  double square_size_m = 0.2;  // checker
};

struct ObjectParams {
  // rectangle | box | cylinder | sphere | ground | led
  std::string shape = "box";
  Eigen::Vector3d size_m = Eigen::Vector3d::Ones();         // rectangle: x, y; box: x, y, z
  double radius_m = 0.15;                                   // cylinder, sphere, led
  double height_m = 1.0;                                    // cylinder
  double intensity = 400.0;                                 // led: blob energy at 1 m
  // rectangle only: holes in (x_O, y_O) [m]. YAML polygon_holes: [[[x, y], ...], ...];
  // ellipse_holes: [[x, y, semi_x, semi_y, angle_deg], ...] (angle from x_O towards y_O).
  std::vector<std::vector<Eigen::Vector2d>> polygon_holes;
  std::vector<EllipseHole> ellipse_holes;
  PoseParams pose;
  bool attach_to_body = false;  // true: pose is T_BO and the object moves with the vehicle
  bool randomize_pose = false;  // jittered by randomize.position_sigma_m / yaw_sigma_deg
  TextureParams texture;
};

struct LightingParams {
  double ambient = 0.35;
  double directional = 0.65;
  Eigen::Vector3d direction_W = Eigen::Vector3d(0.3, 0.2, -1.0);  // direction the light travels
};

// Seeded perturbations (all 0 = off) of the randomizable objects: the gap panel, the gapflyt
// wall, forest trees and boxes, and `objects` with randomize_pose. Textures always derive from
// `seed`.
struct RandomizationParams {
  double position_sigma_m = 0.0;  // per randomizable object, each axis
  double yaw_sigma_deg = 0.0;     // per randomizable object, about z_W
  double light_sigma = 0.0;       // relative jitter of ambient/directional and of the direction
};

struct CameraParams {
  std::string model = "pinhole";  // pinhole | radtan | equidistant (perception camera factory)
  int width = 640;
  int height = 480;
  // Horizontal field of view [deg], used when `intrinsics` is empty: pinhole/radtan
  // f = (w/2) / tan(fov/2), equidistant f = (w/2) / (fov/2 in rad); principal point at the
  // image centre.
  double fov_deg = 90.0;
  Eigen::VectorXd intrinsics;  // [fx, fy, cx, cy] px; empty: from fov_deg
  Eigen::VectorXd distortion;  // model's coefficients (camera_factory.h); empty: zeros
  bool mount_on_body = true;   // false: fixed in the world, `pose` is T_WC
  PoseParams pose;             // T_BC (body mount) or T_WC (world mount)
  double rate_hz = 30.0;
  double latency_s = 0.0;   // SITL: end of exposure -> delivery to the autopilot [s]
  double exposure_s = 0.0;  // > 0 with motion_blur_subframes > 1: motion blur
  int motion_blur_subframes = 1;
  double gain = 1.0;
  double read_noise_sigma = 0.004;    // [fraction of full scale]
  double full_well_electrons = 5000;  // shot noise; 0 = off
  bool color = false;
  bool infrared = false;  // IR mode: dark scene, bright LEDs
  int supersampling = 1;  // k x k rays per pixel; 2 for sub-pixel-accurate edges (4x the cost)
  double drop_probability = 0.0;  // SITL: fraction of frames lost (seeded), in [0, 1)
};

struct TrajectoryParams {
  std::string kind = "hover";  // hover | line | circle | scan | random
  std::string camera;          // camera rendered by `aperture render`; empty: the first
  int frames = 30;             // default frame count; `aperture render --frames` overrides
  // line: start (vehicle.start) -> end_p_m, constant attitude.
  Eigen::Vector3d end_p_m = Eigen::Vector3d::Zero();
  // circle: around center_p_m at the start's height and distance, yawing to face the centre,
  // sweeping arc_deg over the run.
  Eigen::Vector3d center_p_m = Eigen::Vector3d::Zero();
  double arc_deg = 90.0;
  // scan: lateral (body y) sinusoid of amplitude_m with `cycles` periods, while moving from the
  // start towards end_p_m. random: smooth seeded wander of amplitude_m (position) and
  // angle_amplitude_deg (attitude) around the start.
  double amplitude_m = 0.5;
  double cycles = 1.0;
  double angle_amplitude_deg = 10.0;
};

// Patterned gap (seed 000): a white panel with a black rectangular band around a rectangular
// opening (sim/scene/gap_pattern_object.h, the pattern of perception/gap/gap_detector.h); the
// detector sees nested quadrangles (band outer and inner edge). Defaults =
// perception::GapPattern's. Frame G: centre of the opening, z_G along the approach direction (+x_W
// at zero angles), x_G = -y_W, y_G = -z_W (so the pattern reads unmirrored from the approach side);
// roll/pitch rotate about x_W / y_W. Sizes in multiples of 2 cm put every edge on a texel border.
struct GapParams {
  Eigen::Vector3d center_W = Eigen::Vector3d(5.0, 0.0, 1.5);
  double roll_deg = 0.0;   // about x_W (the paper's roll, 0..45 deg)
  double pitch_deg = 0.0;  // about y_W (0..30 deg)
  double yaw_deg = 0.0;    // about z_W
  Eigen::Vector2d opening_m = perception::GapPattern().opening_size_m;  // paper: 80 x 28 cm
  Eigen::Vector2d pattern_inner_m =
      perception::GapPattern().inner_size_m;  // white band's outer edge
  Eigen::Vector2d pattern_outer_m =
      perception::GapPattern().outer_size_m;                 // black band's outer edge
  Eigen::Vector2d panel_m = Eigen::Vector2d(1.7, 1.2);       // white panel
  Eigen::Vector3d room_m = Eigen::Vector3d(14.0, 8.0, 4.0);  // textured room (x from -3 m)

  // The pattern as the detector and the scene object take it (gap_pattern.h).
  perception::GapPattern Pattern() const;
};

// GapFlyt (seed 002): textured foreground wall with an arbitrarily shaped opening and a textured
// background wall, both facing the start (planes x_W = const). Sec. IV: "five different
// arbitrarily shaped gaps as shown in Fig. 8 ... chosen to have a diversity in the geometrical
// sharpness of the corners, convexity of the shape and the size", each "large enough to go
// through" and "near-convex". The seed's text does not give Fig. 8's exact shapes; the five
// `shape` kinds span those axes within the bounding box size_m (w x h; the size axis is size_m):
//   ellipse   no corners, convex; area pi w h / 4
//   polygon   seeded irregular convex quadrilateral, corners 90 +- ~30 deg (or vertices_m)
//   triangle  isosceles, apex up: the sharpest convex corners (apex 2 atan(w / 2h)); area w h / 2
//   notched   the box with a V notch notch_depth_ratio * h deep and w / 2 wide in its top edge:
//             near-convex (area w h (1 - notch_depth_ratio / 4), one reflex corner)
//   star      star_points spikes: sharp tips and strongly non-convex, beyond the paper's
//             near-convex windows (a stress case for the convex-hull / median safe point)
struct GapFlytParams {
  double foreground_x_m = 2.6;
  double background_x_m = 5.7;
  std::string shape = "polygon";  // ellipse | polygon | triangle | notched | star
  Eigen::Vector2d center_m = Eigen::Vector2d(0.0, 1.5);  // (y_W, z_W) of the opening centre
  Eigen::Vector2d size_m = Eigen::Vector2d(1.0, 0.8);    // bounding box (width, height)
  // polygon only: vertices in (x_G right, y_G down) [m] about the centre; empty: a seeded
  // irregular quadrilateral within size_m
  std::vector<Eigen::Vector2d> vertices_m;
  double notch_depth_ratio = 0.2;  // notched: notch depth / height, in (0, 1)
  int star_points = 5;
  double star_inner_ratio = 0.5;
  Eigen::Vector2d foreground_wall_m = Eigen::Vector2d(6.0, 4.0);
  Eigen::Vector2d background_wall_m = Eigen::Vector2d(14.0, 6.0);
};

// Infrared LED target (seed 001 paper C): a quadrotor body whose LEDs a static camera sees.
struct LedSceneParams {
  std::string config;  // YAML file with `leds: [[x, y, z], ...]` [m] in B; overrides `leds`
  std::vector<Eigen::Vector3d> leds_B;  // set by the built-in default (4 LEDs)
  double led_radius_m = 0.004;
  double led_intensity = 600.0;
  int false_spots = 0;  // extra bright emitters at seeded positions (reflections, lamps)
  Eigen::Vector2d false_spot_area_m = Eigen::Vector2d(3.0, 3.0);  // around the target, xy
  double false_spot_height_m = 3.5;
};

// AprilTag mission area (seed 001 paper D, D.3.3): a 4 x 6 m area "with different types of
// obstacles: some of them can be removed by the ground robot ('movable obstacles') and some can
// only be avoided ('fixed obstacles')", a goal representing a victim, the ground robot; "all
// obstacles, the goal, and the ground robot are marked with an AprilTag", plus an origin tag.
// Objects (names, tag ids; every tag lies on the object's top face, z_Tag down into it):
//   origin tag      "tag0" on the ground at the world origin (the map origin)
//   goal            "goal": a flat victim mat of goal_size_m at goal_xy_m, tag 1
//   ground robot    "robot": a box of robot_size_m, tag 2
//   fixed<k>        k = 0 .. fixed_obstacles - 1: boxes of fixed_size_m, tag 3 + k
//   movable<k>      k = 0 .. movable_obstacles - 1: boxes of movable_size_m, tag
//                   3 + fixed_obstacles + k, with the smaller movable_tag_size_m
// Robot and obstacles get seeded positions and yaws inside the area with non-overlapping
// footprints (also clear of the origin tag and the goal); randomize.* does not move them (the
// placement is already seeded; jitter could make footprints overlap). The robot does not drive:
// objects move only with the vehicle (attach_to_body), not on scripted paths.
struct TagsSceneParams {
  Eigen::Vector2d area_m = Eigen::Vector2d(4.0, 6.0);  // x, y extent from the origin tag
  std::string family = "tag36h11";
  double tag_size_m = 0.25;  // origin, goal, robot and fixed obstacles (black border edge)
  // D.3.2: the youBot "is able to lift up to 0.5 kg with its gripper": light 18 cm cubes.
  int movable_obstacles = 3;
  Eigen::Vector3d movable_size_m = Eigen::Vector3d(0.18, 0.18, 0.18);
  double movable_tag_size_m = 0.1;  // its whole pattern (1.25x for tag36h11) fits on the top
  // Fixed obstacles: too large and heavy to lift.
  int fixed_obstacles = 3;
  Eigen::Vector3d fixed_size_m = Eigen::Vector3d(0.5, 0.5, 0.4);
  // D.3.2's KUKA youBot: its base's footprint (data sheet 0.58 x 0.38 m), 15 cm high.
  Eigen::Vector3d robot_size_m = Eigen::Vector3d(0.58, 0.38, 0.15);
  Eigen::Vector2d goal_xy_m = Eigen::Vector2d(3.5, 5.5);
  Eigen::Vector3d goal_size_m = Eigen::Vector3d(0.6, 0.6, 0.01);
};

// Natural environment (seed 003): bark-textured tree trunks, boxes, grass ground.
struct ForestParams {
  int trees = 40;
  int boxes = 6;
  Eigen::Vector2d area_m = Eigen::Vector2d(30.0, 16.0);  // x from 2 m, y centred
  double min_spacing_m = 1.2;  // between trunk centres, and to the flight line y = 0
  Eigen::Vector2d radius_range_m = Eigen::Vector2d(0.12, 0.35);
  Eigen::Vector2d height_range_m = Eigen::Vector2d(4.0, 9.0);
};

struct ScenarioParams {
  std::string scenario = "empty";
  std::uint64_t seed = 0;
  LightingParams lighting;
  RandomizationParams randomize;
  PoseParams vehicle_start;                                   // key vehicle.start
  std::vector<std::pair<std::string, CameraParams>> cameras;  // in document order
  TrajectoryParams trajectory;
  GapParams gap;
  GapFlytParams gapflyt;
  LedSceneParams led;
  TagsSceneParams tags;
  ForestParams forest;
  std::vector<std::pair<std::string, ObjectParams>> objects;  // in document order
  // SITL only: wind, gusts and pushes (key `disturbances`, format in sim/sim_params_io.h).
  DisturbanceParams disturbances;
  // SITL only (ConfigureSitlFromScenario): set when the scenario has the block of that key.
  std::optional<QuadrotorDynamicsParams> dynamics;
  std::optional<ImuSensorParams> imu;
  std::optional<RangeSensorParams> range;
  std::optional<CollisionParams> collision;
  std::optional<SitlRunnerParams> sitl;  // only its loop fields (sim_params_io.h) are read
};

void LoadParams(config::ParamReader& reader, PoseParams* params);
void LoadParams(config::ParamReader& reader, TextureParams* params);
void LoadParams(config::ParamReader& reader, ObjectParams* params);
void LoadParams(config::ParamReader& reader, LightingParams* params);
void LoadParams(config::ParamReader& reader, RandomizationParams* params);
void LoadParams(config::ParamReader& reader, CameraParams* params);
void LoadParams(config::ParamReader& reader, TrajectoryParams* params);
void LoadParams(config::ParamReader& reader, GapParams* params);
void LoadParams(config::ParamReader& reader, GapFlytParams* params);
void LoadParams(config::ParamReader& reader, LedSceneParams* params);
void LoadParams(config::ParamReader& reader, TagsSceneParams* params);
void LoadParams(config::ParamReader& reader, ForestParams* params);
// The whole scenario (root map). Only the section named by `scenario` is accepted; `led.config`
// is read here (relative paths against the working directory).
void LoadParams(config::ParamReader& reader, ScenarioParams* params);

}  // namespace aperture::sim
