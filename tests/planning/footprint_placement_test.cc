// Where the vehicle fits best in an opening: signed distance to a polygon, the level footprint,
// the best placement in a triangle (a band above the base, not the centroid) and in a wide slot
// (nearest the preferred point among equals).
#include "planning/gapflyt/footprint_placement.h"

#include <gtest/gtest.h>

#include <cmath>

namespace aperture::planning {
namespace {

const std::vector<FootprintDisk> kFootprint =
    LevelFootprint(control::VehicleParameters{}, 0.08, 0.0635);

double ClearanceAt(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  return FootprintClearance(polygon, kFootprint, p);
}

TEST(FootprintPlacementTest, SignedDistanceToASquare) {
  const std::vector<Eigen::Vector2d> square{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  EXPECT_DOUBLE_EQ(PolygonSignedDistance(square, {0.0, 0.0}), 1.0);
  EXPECT_DOUBLE_EQ(PolygonSignedDistance(square, {0.5, 0.2}), 0.5);
  EXPECT_DOUBLE_EQ(PolygonSignedDistance(square, {3.0, 0.0}), -2.0);
  EXPECT_NEAR(PolygonSignedDistance(square, {2.0, 2.0}), -std::sqrt(2.0), 1e-12);
}

TEST(FootprintPlacementTest, LevelFootprintLiesOnAHorizontalLine) {
  ASSERT_EQ(kFootprint.size(), 5u);
  const double arm = control::VehicleParameters{}.arm_length_m;
  for (const FootprintDisk& disk : kFootprint) {
    EXPECT_NEAR(disk.offset.y(), 0.0, 1e-12);  // rotor plane edge-on
    if (disk.radius_m == 0.0635) {
      EXPECT_NEAR(std::abs(disk.offset.x()), arm / std::sqrt(2.0), 1e-12);
    }
  }
}

TEST(FootprintPlacementTest, TriangleFitsAboveItsBaseNotAtItsCentroid) {
  // Apex up (y down): base 0.5 m wide at y = +0.4, apex at y = -0.4; the vehicle is 0.38 m wide.
  const std::vector<Eigen::Vector2d> triangle{{0.0, -0.4}, {0.25, 0.4}, {-0.25, 0.4}};
  const FootprintPlacement best = BestFootprintPlacement(triangle, kFootprint);
  EXPECT_NEAR(best.center.x(), 0.0, 1e-3);
  EXPECT_GT(best.center.y(), 0.25);  // in the band above the base
  EXPECT_GT(best.clearance_m, 0.0);
  EXPECT_NEAR(best.clearance_m, ClearanceAt(triangle, best.center), 1e-12);
  const Eigen::Vector2d centroid(0.0, 0.4 - 0.8 / 3.0);
  EXPECT_LT(ClearanceAt(triangle, centroid), 0.0);  // the centroid is too high for the vehicle
  // Nothing around the best is better by more than the search's resolution.
  for (const Eigen::Vector2d& d : {Eigen::Vector2d(0.002, 0), Eigen::Vector2d(0, 0.002),
                                   Eigen::Vector2d(-0.002, 0), Eigen::Vector2d(0, -0.002)}) {
    EXPECT_LE(ClearanceAt(triangle, best.center + d), best.clearance_m + 2e-4);
  }
}

TEST(FootprintPlacementTest, AmongEqualPlacementsTheNearestToThePreferredPoint) {
  const std::vector<Eigen::Vector2d> slot{{-1.0, -0.2}, {1.0, -0.2}, {1.0, 0.2}, {-1.0, 0.2}};
  const FootprintPlacement best = BestFootprintPlacement(slot, kFootprint, {0.5, 0.1});
  EXPECT_NEAR(best.clearance_m, 0.2 - 0.08, 1e-3);  // the body sphere against top and bottom
  EXPECT_NEAR(best.center.x(), 0.5, 0.01);
  EXPECT_NEAR(best.center.y(), 0.0, 1e-3);
  EXPECT_LT(BestFootprintPlacement({{0, 0}, {1, 0}}, kFootprint).clearance_m, 0.0);  // no polygon
}

}  // namespace
}  // namespace aperture::planning
