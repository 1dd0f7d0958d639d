#pragma once
// Where the vehicle fits best in an opening: the body sphere and the propeller disks of a level
// vehicle facing the opening, projected onto the opening's plane (x right, y down [m]), placed to
// maximize the smallest distance from any disk to the opening's edge. For a vehicle as wide as
// the opening this is not the opening's safe point (seed 002's geometric median): in a triangle
// only a band above the base is wide enough. The GapFlyt mission aims its blind line here; the
// bench's tight trials and its evaluator measure openings with the same geometry.
//
//   const auto footprint = LevelFootprint(vehicle, 0.08, 0.0635);
//   const FootprintPlacement best = BestFootprintPlacement(polygon, footprint);
//   if (best.clearance_m > 0.0) aim at best.center;
#include <Eigen/Core>
#include <vector>

#include "control/vehicle_parameters.h"

namespace aperture::planning {

// Distance from p to the closed polygon's edge, positive inside (even-odd rule) [m].
double PolygonSignedDistance(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

struct FootprintDisk {
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  // from the body origin, (x right, y down)
  double radius_m = 0.0;
};

// Body sphere and the propeller disks of the level vehicle facing the plane (x = -y_B, y = -z_B).
std::vector<FootprintDisk> LevelFootprint(const control::VehicleParameters& vehicle,
                                          double body_radius_m, double propeller_radius_m);

// min over disks of (PolygonSignedDistance(polygon, center + offset) - radius) [m].
double FootprintClearance(const std::vector<Eigen::Vector2d>& polygon,
                          const std::vector<FootprintDisk>& footprint,
                          const Eigen::Vector2d& center);

struct FootprintPlacement {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // body origin in the plane [m]
  double clearance_m = 0.0;  // min over disks of (edge distance - radius); < 0: fits nowhere
};

// The best placement: a grid of 5 mm (1/200 of the larger extent for openings over 1 m) over the
// polygon's bounds, then 0.5 mm around the best. Ties (a band of equal clearance, e.g. a wide
// rectangle) go to the placement nearest `prefer`.
FootprintPlacement BestFootprintPlacement(const std::vector<Eigen::Vector2d>& polygon,
                                          const std::vector<FootprintDisk>& footprint,
                                          const Eigen::Vector2d& prefer = Eigen::Vector2d::Zero());

}  // namespace aperture::planning
