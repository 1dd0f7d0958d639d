#pragma once
// Tight trials of `aperture bench gapflyt` (issue 14: "trials whose narrowest opening is only 5 cm
// wider than the vehicle"): the opening is stretched sideways until the vehicle, level and placed
// as well as it can be (planning/gapflyt/footprint_placement.h), clears the edge by margin / 2 on
// its tightest side — the narrowest passage is then `margin` wider than the vehicle, whatever the
// shape (a star's bounding box must be wider than an ellipse's for that).
//
// The footprint is what GapflytEvaluation measures at the crossing: the body sphere and the four
// propeller disks (sim::CollisionParams) projected along the wall normal, here level.
//
//   config.size_m.x() = TightOpeningWidthM(OpeningFromScene(scene), config.size_m.x(),
//                                          BenchFootprint(), 0.05);
#include <vector>

#include "experiments/gapflyt/gapflyt_evaluation.h"
#include "planning/gapflyt/footprint_placement.h"

namespace aperture::experiments {

// The default vehicle's level footprint with the collision checker's radii.
std::vector<planning::FootprintDisk> BenchFootprint();

// The width (bounding box, x_O) to give `opening`, whose bounding width is now `width_m`, by
// stretching it along x_O (height unchanged), so that the best placement's clearance is
// margin_m / 2 (bisection to 0.1 mm). Throws std::invalid_argument when even a 20x wider opening
// leaves less (the opening is lower than the footprint) or margin_m < 0.
double TightOpeningWidthM(const GapflytOpening& opening, double width_m,
                          const std::vector<planning::FootprintDisk>& footprint, double margin_m);

}  // namespace aperture::experiments
