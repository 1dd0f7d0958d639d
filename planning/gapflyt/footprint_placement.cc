#include "planning/gapflyt/footprint_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aperture::planning {
namespace {

double DistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-18), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

}  // namespace

double PolygonSignedDistance(const std::vector<Eigen::Vector2d>& polygon,
                             const Eigen::Vector2d& p) {
  bool inside = false;
  double distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    // Even-odd crossing test of the ray +x from p.
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
    distance = std::min(distance, DistanceToSegment(p, a, b));
  }
  return inside ? distance : -distance;
}

double FootprintClearance(const std::vector<Eigen::Vector2d>& polygon,
                          const std::vector<FootprintDisk>& footprint,
                          const Eigen::Vector2d& center) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const FootprintDisk& disk : footprint) {
    clearance =
        std::min(clearance, PolygonSignedDistance(polygon, center + disk.offset) - disk.radius_m);
  }
  return clearance;
}

std::vector<FootprintDisk> LevelFootprint(const control::VehicleParameters& vehicle,
                                          double body_radius_m, double propeller_radius_m) {
  std::vector<FootprintDisk> footprint{{Eigen::Vector2d::Zero(), body_radius_m}};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d rotor_B = vehicle.RotorPosition_B(i);
    footprint.push_back({Eigen::Vector2d(-rotor_B.y(), -rotor_B.z()), propeller_radius_m});
  }
  return footprint;
}

FootprintPlacement BestFootprintPlacement(const std::vector<Eigen::Vector2d>& polygon,
                                          const std::vector<FootprintDisk>& footprint,
                                          const Eigen::Vector2d& prefer) {
  FootprintPlacement best{prefer, -std::numeric_limits<double>::infinity()};
  if (polygon.size() < 3) return best;
  Eigen::Vector2d lo = polygon.front(), hi = lo;
  for (const Eigen::Vector2d& v : polygon) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const auto search = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& to, double step) {
    for (double y = from.y(); y <= to.y(); y += step) {
      for (double x = from.x(); x <= to.x(); x += step) {
        const Eigen::Vector2d p(x, y);
        const double clearance = FootprintClearance(polygon, footprint, p);
        // Better by more than 0.1 mm, or as good and nearer the preferred point.
        if (clearance > best.clearance_m + 1e-4 ||
            (clearance > best.clearance_m - 1e-4 &&
             (p - prefer).squaredNorm() < (best.center - prefer).squaredNorm())) {
          best = {p, std::max(clearance, best.clearance_m)};
        }
      }
    }
  };
  const double coarse = std::max(0.005, (hi - lo).maxCoeff() / 200.0);
  search(lo, hi, coarse);
  const Eigen::Vector2d around(coarse, coarse);
  search(best.center - around, best.center + around, 0.0005);
  best.clearance_m = FootprintClearance(polygon, footprint, best.center);
  return best;
}

}  // namespace aperture::planning
