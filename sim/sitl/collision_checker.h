#pragma once
// Collision test of the vehicle against the scene and the ground plane. The vehicle is a sphere of
// radius body_radius_m around the origin of B plus four propeller disks of radius
// propeller_radius_m in the rotor plane z_B = 0, centred on the rotors (VehicleParameters::
// RotorPosition_B), plus the arms from the origin of B to each rotor.
//
// Ground (z_W = QuadrotorDynamicsParams::ground_height_m, the plane the dynamics' landing gear
// rests on, so there is one ground): exact -- the lowest point of the sphere and of every disk.
// With the dynamics' ground contact on, the vehicle may rest on its landing gear (origin of B
// landing_gear_height_m up, which must exceed body_radius_m); CheckTouchdown then judges each
// touchdown: faster than max_touchdown_speed_mps or tilted more than max_touchdown_tilt_rad is a
// crash ("landing gear" with "ground"), a gentler one a contact the vehicle rests from.
// Scene objects: through the scene's ray queries (Scene::Intersect), so every primitive works
// without a distance function:
//   * sphere: `sphere_rays` rays from the centre, directions on a Fibonacci sphere, length radius;
//   * disks: `disk_rays` radial rays in each disk's plane, length propeller_radius_m;
//   * arms: one ray per arm;
//   * sweep: the segment from the previous to the current centre (no tunnelling through thin
//     walls between two checks).
// The ray test is conservative to within the angular spacing of the rays: a flat surface is
// detected once it is closer than radius * cos(half the spacing) (~0.93 radius for 64 rays);
// a thin edge (a hole's rim) may pass between rays of the sphere by up to that gap. LEDs are not
// solid (Scene::Intersect ignores them); neither are `ignored_objects` (rays continue past them).
// Only objects whose bounding sphere comes within the vehicle's reach of the swept segment are
// ray-tested (the same hits as testing all, at ~0 cost far from obstacles).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "control/quad_state.h"
#include "control/vehicle_parameters.h"
#include "sim/scene/scene.h"
#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::sim {

struct CollisionParams {
  double body_radius_m = 0.08;         // frame + electronics of a ~0.45 kg, 0.178 m-arm vehicle
  double propeller_radius_m = 0.0635;  // 5 inch propellers
  bool ground_enabled = true;          // the dynamics' ground plane is solid
  // With ground contact: the hardest touchdown the landing gear survives. 1 m/s is a firm landing
  // for a ~0.5 kg quadrotor; 0.5 rad (~29 deg) of tilt tips it over onto a propeller.
  double max_touchdown_speed_mps = 1.0;
  double max_touchdown_tilt_rad = 0.5;
  // Scene objects that are not obstacles (e.g. parts attached to the vehicle body, markers).
  std::vector<std::string> ignored_objects;
  int sphere_rays = 64;
  int disk_rays = 12;
  // Throws std::invalid_argument naming the field (radii or touchdown limits <= 0 or non-finite,
  // ray counts < 6).
  void Validate() const;
};

struct Collision {
  std::string object_name;  // "ground" for the ground plane, else the scene object's name
  std::string part;         // "body", "propeller 1".."propeller 4", "arm 1".."arm 4", "sweep"
  Eigen::Vector3d contact_p_W = Eigen::Vector3d::Zero();  // first surface point reached [m]
};

class CollisionChecker {
 public:
  // The vehicle geometry, ground height and landing gear come from `dynamics`. Throws
  // std::invalid_argument for invalid params, and when ground contact is on with the gear not
  // above the body sphere (resting would be a crash).
  CollisionChecker(const QuadrotorDynamicsParams& dynamics, const CollisionParams& params);
  // The constructor's checks alone: throws std::invalid_argument as it would.
  static void Validate(const QuadrotorDynamicsParams& dynamics, const CollisionParams& params);
  // First collision of the vehicle at `state`, having moved from previous_p_WB since the last
  // check (pass state.p_WB for none); std::nullopt when clear. `scene` may be null (ground only).
  std::optional<Collision> Check(const Scene* scene, const control::QuadState& state,
                                 const Eigen::Vector3d& previous_p_WB) const;
  // A touchdown on the landing gear at p_WB with the vehicle's speed and tilt then
  // (QuadrotorDynamics::last_touchdown_*): a ground collision of part "landing gear" at the point
  // below p_WB when beyond the limits (and ground_enabled), else std::nullopt.
  std::optional<Collision> CheckTouchdown(const Eigen::Vector3d& p_WB, double speed_mps,
                                          double tilt_rad) const;
  const CollisionParams& params() const { return params_; }

 private:
  CollisionParams params_;
  double ground_height_m_ = 0.0;
  std::vector<Eigen::Vector3d> rotor_positions_B_;
  std::vector<Eigen::Vector3d> sphere_directions_;
  std::vector<Eigen::Vector3d> disk_directions_B_;  // unit, in the plane z_B = 0
  double reach_m_ = 0.0;  // farthest point of the vehicle from the origin of B [m]
};

}  // namespace aperture::sim
