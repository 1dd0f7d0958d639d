// Tight GapFlyt openings: the footprint's best clearance in a rectangle is analytic, a rectangle's
// tight width is the vehicle's width plus the margin, and every shape stretched to its tight width
// leaves margin / 2 at the best placement (a star needs a wider bounding box than an ellipse).
#include "experiments/gapflyt/tight_opening.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/scenario/scenario.h"

namespace aperture::experiments {
namespace {

GapflytOpening Rectangle(double width_m, double height_m) {
  GapflytOpening opening;
  const double w = width_m / 2, h = height_m / 2;
  opening.polygon_O = {{-w, -h}, {w, -h}, {w, h}, {-w, h}};
  return opening;
}

// Half the footprint's width and height (the disks' outer extents).
Eigen::Vector2d HalfExtent(const std::vector<planning::FootprintDisk>& footprint) {
  Eigen::Vector2d half = Eigen::Vector2d::Zero();
  for (const planning::FootprintDisk& disk : footprint) {
    half = half.cwiseMax(disk.offset.cwiseAbs() + Eigen::Vector2d::Constant(disk.radius_m));
  }
  return half;
}

const std::vector<planning::FootprintDisk> kFootprint = BenchFootprint();

TEST(TightOpeningTest, LevelFootprintSpansTheRotorDisks) {
  const control::VehicleParameters vehicle;
  const sim::CollisionParams collision;
  ASSERT_EQ(kFootprint.size(), 5u);
  EXPECT_NEAR(HalfExtent(kFootprint).x(),
              vehicle.arm_length_m / std::sqrt(2.0) + collision.propeller_radius_m, 1e-12);
  EXPECT_NEAR(HalfExtent(kFootprint).y(),
              std::max(collision.body_radius_m, collision.propeller_radius_m), 1e-12);
}

TEST(TightOpeningTest, RectangleClearanceAndTightWidthAreAnalytic) {
  const Eigen::Vector2d half = HalfExtent(kFootprint);
  // Centred in a 0.6 x 0.5 m rectangle the footprint clears the sides by 0.3 - half.x.
  EXPECT_NEAR(
      planning::BestFootprintPlacement(Rectangle(0.6, 0.5).polygon_O, kFootprint).clearance_m,
      0.3 - half.x(), 5e-4);
  // Tight: the rectangle's width is the footprint's width plus the margin.
  const double width = TightOpeningWidthM(Rectangle(1.0, 0.8), 1.0, kFootprint, 0.05);
  EXPECT_NEAR(width, 2.0 * half.x() + 0.05, 1e-3);
  EXPECT_THROW(TightOpeningWidthM(Rectangle(1.0, 0.8), 1.0, kFootprint, -0.01),
               std::invalid_argument);
  EXPECT_THROW(TightOpeningWidthM(Rectangle(1.0, 0.1), 1.0, kFootprint, 0.05),
               std::invalid_argument);  // lower than the footprint
}

// Every scenario shape at its tight width: the best placement clears by margin / 2.
TEST(TightOpeningTest, EveryShapeAtItsTightWidthLeavesHalfTheMargin) {
  double ellipse_width = 0.0, star_width = 0.0;
  for (const std::string shape : {"ellipse", "polygon", "triangle", "notched", "star"}) {
    sim::ScenarioParams params = sim::LoadScenarioParams(sim::ScenarioConfig("gapflyt"));
    params.seed = 3;
    params.gapflyt.shape = shape;
    params.gapflyt.size_m = Eigen::Vector2d(1.0, 0.8);
    const GapflytOpening opening = OpeningFromScene(sim::BuildScenario(params).scene());
    const double width = TightOpeningWidthM(opening, 1.0, kFootprint, 0.05);
    params.gapflyt.size_m.x() = width;
    const GapflytOpening tight = OpeningFromScene(sim::BuildScenario(params).scene());
    EXPECT_NEAR(planning::BestFootprintPlacement(tight.polygon_O, kFootprint).clearance_m, 0.025,
                1e-3)
        << shape;
    if (shape == "ellipse") ellipse_width = width;
    if (shape == "star") star_width = width;
  }
  EXPECT_GT(star_width, 1.25 * ellipse_width);  // 0.59 vs 0.43 m at this seed
}

}  // namespace
}  // namespace aperture::experiments
