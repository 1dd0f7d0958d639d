#include "experiments/gapflyt/tight_opening.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace aperture::experiments {
namespace {

double FootprintClearance(const GapflytOpening& opening,
                          const std::vector<FootprintDisk>& footprint, const Eigen::Vector2d& p_O) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const FootprintDisk& disk : footprint) {
    clearance = std::min(clearance, opening.SignedDistance(p_O + disk.offset_O) - disk.radius_m);
  }
  return clearance;
}

GapflytOpening StretchedX(const GapflytOpening& opening, double factor) {
  GapflytOpening stretched = opening;
  for (Eigen::Vector2d& v : stretched.polygon_O) v.x() *= factor;
  return stretched;
}

}  // namespace

std::vector<FootprintDisk> LevelFootprint(const control::VehicleParameters& vehicle,
                                          const sim::CollisionParams& collision) {
  std::vector<FootprintDisk> footprint{{Eigen::Vector2d::Zero(), collision.body_radius_m}};
  for (int i = 0; i < 4; ++i) {
    // Facing +z_O (= x_B), level: x_O = -y_B, y_O = -z_B.
    const Eigen::Vector3d rotor_B = vehicle.RotorPosition_B(i);
    footprint.push_back(
        {Eigen::Vector2d(-rotor_B.y(), -rotor_B.z()), collision.propeller_radius_m});
  }
  return footprint;
}

double BestFootprintClearanceM(const GapflytOpening& opening,
                               const std::vector<FootprintDisk>& footprint) {
  Eigen::Vector2d lo = opening.polygon_O.front(), hi = lo;
  for (const Eigen::Vector2d& v : opening.polygon_O) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  double best = -std::numeric_limits<double>::infinity();
  Eigen::Vector2d best_p = 0.5 * (lo + hi);
  const auto search = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& to, double step) {
    for (double y = from.y(); y <= to.y(); y += step) {
      for (double x = from.x(); x <= to.x(); x += step) {
        const double clearance = FootprintClearance(opening, footprint, {x, y});
        if (clearance > best) best = clearance, best_p = {x, y};
      }
    }
  };
  // Coarse (5 mm, or 1/200 of the larger extent for wide openings), then 0.5 mm around the best.
  const double coarse = std::max(0.005, (hi - lo).maxCoeff() / 200.0);
  search(lo, hi, coarse);
  const Eigen::Vector2d around(coarse, coarse);
  search(best_p - around, best_p + around, 0.0005);
  return best;
}

double TightOpeningWidthM(const GapflytOpening& opening, double width_m,
                          const std::vector<FootprintDisk>& footprint, double margin_m) {
  if (!(margin_m >= 0.0) || !(width_m > 0.0)) {
    throw std::invalid_argument("TightOpeningWidthM: margin_m must be >= 0 and width_m > 0, got " +
                                std::to_string(margin_m) + ", " + std::to_string(width_m));
  }
  const double target = 0.5 * margin_m;
  const auto clearance_at = [&](double factor) {
    return BestFootprintClearanceM(StretchedX(opening, factor), footprint);
  };
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
