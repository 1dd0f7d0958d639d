// The lawn-mower coverage planner (planning/tag_mapping/lawn_mower_coverage.h): the height rule
// against the projected tag, the footprint against the pinhole's closed form, and the coverage
// invariants (every field point inside some camera position's reduced footprint, adjacent
// footprints sharing the stated overlap, no track more than needed) over fields, footprints and
// overlaps.
#include "planning/tag_mapping/lawn_mower_coverage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "perception/camera/pinhole_camera.h"

namespace aperture::planning {
namespace {

const perception::PinholeCamera kCamera(640, 480, {320.0, 320.0, 319.5, 239.5});

// Side of a tag of edge size_m lying flat depth_m below a camera looking straight down, in pixels
// (the projected edge through the image centre).
double ProjectedSidePx(double size_m, double depth_m) {
  Eigen::Vector2d a, b;
  EXPECT_TRUE(kCamera.Project(Eigen::Vector3d(-size_m / 2, 0.0, depth_m), &a));
  EXPECT_TRUE(kCamera.Project(Eigen::Vector3d(size_m / 2, 0.0, depth_m), &b));
  return (b - a).norm();
}

TEST(LawnMowerCoverage, CentralFocalLengthIsThePinholes) {
  EXPECT_NEAR(CentralFocalLengthPx(kCamera), 320.0, 1e-6);
}

TEST(LawnMowerCoverage, HeightKeepsTheSmallestTagAtTheRequiredPixels) {
  // The `tags` scenario's classes: 0.25 m tags on the ground and on 0.4 m blocks, 0.1 m tags on
  // 0.18 m cubes. The cubes' tags bind: 0.18 + 320 * 0.1 / 14.
  const std::vector<TagClass> classes{{0.25, 0.0}, {0.25, 0.4}, {0.1, 0.18}};
  const double h = MappingHeight(320.0, classes, 14.0);
  EXPECT_NEAR(h, 0.18 + 320.0 * 0.1 / 14.0, 1e-12);
  EXPECT_NEAR(ProjectedSidePx(0.1, h - 0.18), 14.0, 1e-9);
  for (const TagClass& c : classes)
    EXPECT_GE(ProjectedSidePx(c.size_m, h - c.surface_height_m), 14.0 - 1e-9);
  // 1 cm higher the small tag falls below the rule: the height is the highest that keeps it.
  EXPECT_LT(ProjectedSidePx(0.1, h + 0.01 - 0.18), 14.0);
  EXPECT_THROW(MappingHeight(320.0, {}, 14.0), std::invalid_argument);
  EXPECT_THROW(MappingHeight(320.0, {{0.0, 0.0}}, 14.0), std::invalid_argument);
  EXPECT_THROW(MappingHeight(320.0, classes, 0.0), std::invalid_argument);
}

TEST(LawnMowerCoverage, FootprintOfAPinholeLookingDownIsItsClosedForm) {
  const Footprint f = FootprintAtDepth(kCamera, 2.0);
  EXPECT_NEAR(f.half_x_m, 2.0 * 319.5 / 320.0, 1e-9);
  EXPECT_NEAR(f.half_y_m, 2.0 * 239.5 / 320.0, 1e-9);
  EXPECT_THROW(FootprintAtDepth(kCamera, 0.0), std::invalid_argument);
}

// Distance of p from the set of camera positions in the footprint's metric: covered iff some
// track point c has |across(p - c)| <= a and |along(p - c)| <= b.
bool Covered(const LawnMowerPlan& plan, const Eigen::Vector2d& p) {
  const Eigen::Vector2d along = plan.track_direction_W;
  const Eigen::Vector2d across(-along.y(), along.x());
  for (std::size_t k = 0; k + 1 < plan.camera_waypoints_W.size(); k += 2) {
    const Eigen::Vector2d a = plan.camera_waypoints_W[k].head<2>();
    const Eigen::Vector2d b = plan.camera_waypoints_W[k + 1].head<2>();
    if (std::abs(across.dot(p - a)) > plan.half_across_m + 1e-9) continue;
    const double s0 = std::min(along.dot(a), along.dot(b)),
                 s1 = std::max(along.dot(a), along.dot(b));
    const double s = along.dot(p);
    const double gap = s < s0 ? s0 - s : (s > s1 ? s - s1 : 0.0);
    if (gap <= plan.half_along_m + 1e-9) return true;
  }
  return false;
}

TEST(LawnMowerCoverage, TracksCoverTheFieldWithTheStatedOverlap) {
  struct Case {
    FieldRectangle field;
    double half_across_m, half_along_m, overlap;
  };
  const std::vector<Case> cases{
      {{{0.0, 0.0}, {4.0, 6.0}}, 1.84, 1.33, 0.5},  // the `tags` field at ~2.5 m
      {{{0.0, 0.0}, {4.0, 6.0}}, 1.84, 1.33, 0.0},
      {{{-3.0, 1.0}, {9.0, 3.5}}, 1.0, 0.6, 0.3},  // tracks along x
      {{{0.0, 0.0}, {1.0, 1.5}}, 2.0, 1.5, 0.2},   // narrower than one footprint
      {{{0.0, 0.0}, {20.0, 20.0}}, 0.7, 0.5, 0.75},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << "field " << c.field.max_W.transpose() << ", overlap "
                                    << c.overlap << ", half across " << c.half_across_m);
    const LawnMowerPlan plan =
        PlanLawnMower(c.field, 2.5, c.half_across_m, c.half_along_m, c.overlap);
    const Eigen::Vector2d extent = c.field.max_W - c.field.min_W;
    const int along_axis = extent.y() >= extent.x() ? 1 : 0;
    EXPECT_TRUE(plan.track_direction_W == Eigen::Vector2d::Unit(along_axis));
    ASSERT_EQ(static_cast<int>(plan.camera_waypoints_W.size()), 2 * plan.tracks);
    for (const Eigen::Vector3d& p : plan.camera_waypoints_W) EXPECT_EQ(p.z(), 2.5);
    // Every point of the field (a 5 cm grid, edges included) is seen.
    for (double x = c.field.min_W.x(); x <= c.field.max_W.x() + 1e-9; x += 0.05) {
      for (double y = c.field.min_W.y(); y <= c.field.max_W.y() + 1e-9; y += 0.05) {
        ASSERT_TRUE(Covered(plan, {std::min(x, c.field.max_W.x()), std::min(y, c.field.max_W.y())}))
            << "(" << x << ", " << y << ") is not covered";
      }
    }
    // Adjacent footprints share at least 2 a o; the outer ones reach o a past the long edges.
    const int across_axis = 1 - along_axis;
    if (plan.tracks > 1) {
      EXPECT_LE(plan.track_spacing_m, 2.0 * c.half_across_m * (1.0 - c.overlap) + 1e-9);
      for (int k = 0; k + 1 < plan.tracks; ++k) {
        const double step = plan.camera_waypoints_W[2 * k + 2](across_axis) -
                            plan.camera_waypoints_W[2 * k](across_axis);
        EXPECT_GE(2.0 * c.half_across_m - step, 2.0 * c.half_across_m * c.overlap - 1e-9);
      }
      EXPECT_LE(plan.camera_waypoints_W.front()(across_axis) - c.half_across_m,
                c.field.min_W(across_axis) - c.overlap * c.half_across_m + 1e-9);
      EXPECT_GE(plan.camera_waypoints_W.back()(across_axis) + c.half_across_m,
                c.field.max_W(across_axis) + c.overlap * c.half_across_m - 1e-9);
    }
    // No more tracks than needed: one fewer could not keep the spacing bound.
    if (plan.tracks > 2) {
      const double span = plan.track_spacing_m * (plan.tracks - 1);
      EXPECT_GT(span / (plan.tracks - 2), 2.0 * c.half_across_m * (1.0 - c.overlap));
    }
    // Boustrophedon: consecutive tracks run in opposite directions, each starting where the
    // previous one ended.
    for (int k = 0; k + 1 < plan.tracks; ++k) {
      EXPECT_NEAR(plan.camera_waypoints_W[2 * k + 1](along_axis),
                  plan.camera_waypoints_W[2 * k + 2](along_axis), 1e-12);
    }
  }
}

TEST(LawnMowerCoverage, RejectsAnEmptyFieldFootprintOrBadOverlap) {
  const FieldRectangle field{{0.0, 0.0}, {4.0, 6.0}};
  EXPECT_THROW(PlanLawnMower({{0.0, 0.0}, {0.0, 6.0}}, 2.5, 1.0, 1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(PlanLawnMower(field, 2.5, -0.1, 1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(PlanLawnMower(field, 2.5, 1.0, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(PlanLawnMower(field, 2.5, 1.0, 1.0, -0.1), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
