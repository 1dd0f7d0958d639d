#pragma once
// Success of a gap flight by the vehicle's footprint (issue 21, item 4): the body sphere, the four
// propeller disks and the arms (the geometry of sim/sitl/collision_checker.h) against the gap
// panel, analytically. The panel is the plane z_G = 0 of the gap frame: the rectangle panel_m
// (centred on the opening) minus the opening rectangle. At each pose the parts' sections by
// that plane are exact (a circle for the sphere, a chord for a disk, a point for an arm);
// contact means a section reaches the panel (touching the opening's rim counts). Poses are taken
// at the recorded states and between them, close enough that no point of the vehicle moves more
// than max_step_m from one pose to the next, so nothing passes between two tests.
//
//   const VehicleFootprint footprint = VehicleFootprintOf(sitl.dynamics.vehicle, sitl.collision);
//   if (auto contact = FindFootprintContact(result.trajectory, gap, footprint)) ...
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "control/quad_state.h"
#include "control/vehicle_parameters.h"
#include "experiments/gap/gap_geometry.h"
#include "sim/sitl/collision_checker.h"

namespace aperture::experiments {

struct VehicleFootprint {
  double body_radius_m = 0.08;                 // sphere about the origin of B
  double propeller_radius_m = 0.0635;          // disks in the rotor plane z_B = 0
  std::array<Eigen::Vector3d, 4> rotor_p_B{};  // disk centres = arm ends [m]
  // Largest distance of a footprint point from the origin of B [m].
  double ReachM() const;
  // Throws std::invalid_argument naming the field for non-positive or non-finite sizes.
  void Validate() const;
};

// The SITL's collision geometry: body and propeller radii of `collision`, rotors of `vehicle`.
VehicleFootprint VehicleFootprintOf(const control::VehicleParameters& vehicle,
                                    const sim::CollisionParams& collision);

struct FootprintContact {
  double t_s = 0.0;
  std::string part;  // "body", "propeller 1".."propeller 4", "arm 1".."arm 4"
  Eigen::Vector2d p_G_m = Eigen::Vector2d::Zero();  // a point of the section on the panel
};

// First contact of the footprint at `state` with the panel of `gap`; nullopt when clear.
std::optional<FootprintContact> FootprintContactAt(const control::QuadState& state,
                                                   const GapGeometry& gap,
                                                   const VehicleFootprint& footprint,
                                                   double max_step_m = 0.002);

// First contact along the trajectory (interpolated as GroundTruthAt between samples, poses at
// most max_step_m of motion apart); nullopt when the footprint never meets the panel. Throws
// std::invalid_argument for an invalid footprint, opening, panel or max_step_m <= 0.
std::optional<FootprintContact> FindFootprintContact(
    const std::vector<control::QuadState>& trajectory, const GapGeometry& gap,
    const VehicleFootprint& footprint, double max_step_m = 0.002);

}  // namespace aperture::experiments
