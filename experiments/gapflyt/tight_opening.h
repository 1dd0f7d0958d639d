#pragma once
// Tight trials of `aperture bench gapflyt` (issue 14: "trials whose narrowest opening is only 5 cm
// wider than the vehicle"): the opening is stretched sideways until the vehicle, level and placed
// as well as it can be, clears the edge by margin / 2 on its tightest side — the narrowest passage
// is then `margin` wider than the vehicle, whatever the shape (a star's bounding box must be much
// wider than a rectangle's for that).
//
// The footprint is what GapflytEvaluation measures at the crossing: the body sphere and the four
// propeller disks projected along the wall normal, here for a level vehicle facing the wall.
//
//   const auto footprint = LevelFootprint(vehicle, collision);
//   config.size_m.x() = TightOpeningWidthM(OpeningFromScene(scene), config.size_m.x(), footprint,
//                                          0.05);
#include <Eigen/Core>
#include <vector>

#include "control/vehicle_parameters.h"
#include "experiments/gapflyt/gapflyt_evaluation.h"
#include "sim/sitl/collision_checker.h"

namespace aperture::experiments {

struct FootprintDisk {
  Eigen::Vector2d offset_O = Eigen::Vector2d::Zero();  // from the body origin, (x_O right, y_O down)
  double radius_m = 0.0;
};

// Body sphere and propeller disks of the level vehicle facing +z_O (rotor plane edge-on).
std::vector<FootprintDisk> LevelFootprint(const control::VehicleParameters& vehicle,
                                          const sim::CollisionParams& collision);

// max over body positions p of min over disks (SignedDistance(p + offset) - radius) [m]: the
// clearance of the best placement (a grid of 5 mm, coarser for openings over 1 m, over the
// polygon's bounds, then refined to 0.5 mm).
// Negative when the footprint fits nowhere.
double BestFootprintClearanceM(const GapflytOpening& opening,
                               const std::vector<FootprintDisk>& footprint);

// The width (bounding box, x_O) to give `opening`, whose bounding width is now `width_m`, by
// stretching it along x_O (height unchanged), so that BestFootprintClearanceM = margin_m / 2
// (bisection to 0.1 mm). Throws std::invalid_argument when even a 20x wider opening leaves less
// (the opening is lower than the footprint) or margin_m < 0.
double TightOpeningWidthM(const GapflytOpening& opening, double width_m,
                          const std::vector<FootprintDisk>& footprint, double margin_m);

}  // namespace aperture::experiments
