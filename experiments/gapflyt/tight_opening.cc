#include "experiments/gapflyt/tight_opening.h"

#include <stdexcept>
#include <string>

#include "control/vehicle_parameters.h"
#include "sim/sitl/collision_checker.h"

namespace aperture::experiments {

std::vector<planning::FootprintDisk> BenchFootprint() {
  const sim::CollisionParams collision;
  return planning::LevelFootprint(control::VehicleParameters{}, collision.body_radius_m,
                                  collision.propeller_radius_m);
}

double TightOpeningWidthM(const GapflytOpening& opening, double width_m,
                          const std::vector<planning::FootprintDisk>& footprint, double margin_m) {
  if (!(margin_m >= 0.0) || !(width_m > 0.0)) {
    throw std::invalid_argument("TightOpeningWidthM: margin_m must be >= 0 and width_m > 0, got " +
                                std::to_string(margin_m) + ", " + std::to_string(width_m));
  }
  const auto clearance_at = [&](double factor) {
    std::vector<Eigen::Vector2d> stretched = opening.polygon_O;
    for (Eigen::Vector2d& v : stretched) v.x() *= factor;
    return planning::BestFootprintPlacement(stretched, footprint).clearance_m;
  };
  const double target = 0.5 * margin_m;
  double low = 0.0, high = 20.0;  // stretch factors
  if (clearance_at(high) < target) {
    throw std::invalid_argument(
        "TightOpeningWidthM: the opening is too low for the vehicle's footprint at any width");
  }
  while ((high - low) * width_m > 1e-4) {
    const double mid = 0.5 * (low + high);
    (clearance_at(mid) >= target ? high : low) = mid;
  }
  return high * width_m;
}

}  // namespace aperture::experiments
