// FlownTrail: the flown path ForestMission backs off along (beyond seed 003).
#include "planning/mono_nav/flown_trail.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace aperture::planning {
namespace {

TEST(FlownTrail, KeepsPointsAtTheSpacingAndBacksOffAlongThemLatestFirst) {
  FlownTrail trail(0.1);
  // Flown: 1.2 m along x in 3 cm steps, then 0.6 m along y: a point is kept every 4th step
  // (0.12 m; 0.09 m is under the spacing).
  for (int k = 0; k <= 40; ++k) trail.Add(Eigen::Vector3d(0.03 * k, 0.0, 1.5));
  for (int k = 1; k <= 20; ++k) trail.Add(Eigen::Vector3d(1.2, 0.03 * k, 1.5));
  ASSERT_EQ(trail.points_W().size(), 11u + 5u);
  EXPECT_TRUE(trail.points_W()[10].isApprox(Eigen::Vector3d(1.2, 0.0, 1.5), 1e-9));
  EXPECT_TRUE(trail.points_W().back().isApprox(Eigen::Vector3d(1.2, 0.6, 1.5), 1e-9));

  // 0.8 m back from (1.2, 0.65): 0.05 m to the latest point, 0.6 m down y to the corner, then
  // along x until the length reaches 0.8 m: two more points, ending at x = 0.96 (0.89 m).
  const Eigen::Vector3d p_W(1.2, 0.65, 1.5);
  const std::vector<Eigen::Vector3d> path_W = trail.BackOffPath(p_W, 0.8);
  ASSERT_EQ(path_W.size(), 1u + 5u + 1u + 2u);
  EXPECT_TRUE(path_W.front().isApprox(p_W));
  EXPECT_TRUE(path_W[6].isApprox(Eigen::Vector3d(1.2, 0.0, 1.5), 1e-9));
  EXPECT_TRUE(path_W.back().isApprox(Eigen::Vector3d(0.96, 0.0, 1.5), 1e-9));
  EXPECT_NEAR(PolylineLength(path_W), 0.89, 1e-9);

  // Flying it consumes the points flown over; its end is the latest point.
  trail.Retrace(path_W);
  ASSERT_EQ(trail.points_W().size(), 9u);
  EXPECT_TRUE(trail.points_W().back().isApprox(Eigen::Vector3d(0.96, 0.0, 1.5), 1e-9));
  // The next back-off continues from there and stops at the trail's start.
  const std::vector<Eigen::Vector3d> rest_W = trail.BackOffPath(trail.points_W().back(), 5.0);
  EXPECT_NEAR(PolylineLength(rest_W), 0.96, 1e-9);
  EXPECT_TRUE(rest_W.back().isApprox(Eigen::Vector3d(0.0, 0.0, 1.5), 1e-9));

  // Nothing flown: the path is where the vehicle is.
  EXPECT_EQ(FlownTrail(0.1).BackOffPath(p_W, 1.0).size(), 1u);
  EXPECT_THROW(FlownTrail(0.0), std::invalid_argument);
  EXPECT_THROW(FlownTrail(0.1).Retrace(path_W), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
