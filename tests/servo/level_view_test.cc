#include "servo/level_view.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "free_camera_simulation.h"

namespace aperture::servo {
namespace {

// Truth: the level camera's own projection of the same world points (same optical centre: a
// rotation is all an image can undo without depth).
TEST(LevelViewTest, TiltedViewMatchesTheLevelCameraAtTheSamePositionAndHeading) {
  const std::vector<Eigen::Vector3d> points_W = {
      {3.0, 0.4, 1.9}, {3.0, -0.5, 1.2}, {3.2, 0.1, 1.5}, {2.5, -0.2, 1.8}};
  for (const Eigen::Isometry3d& T_BC :
       {testing::ForwardCameraMount(), testing::DownwardCameraMount()}) {
    std::vector<Eigen::Vector3d> points = points_W;
    if (T_BC.linear()(2, 2) < 0.0) {  // downward camera: points on the ground below instead
      for (Eigen::Vector3d& p : points) p = Eigen::Vector3d(0.3 * p.y(), 0.2 * p.z(), 0.0);
    }
    const Eigen::Isometry3d T_WB_level = testing::LevelPose({0.2, 0.1, 1.5}, 0.4);
    Eigen::Isometry3d T_WB_tilted = T_WB_level;
    T_WB_tilted.linear() =
        T_WB_level.linear() * (Eigen::AngleAxisd(0.25, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(-0.15, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    const auto tilted = testing::FreeCameraSimulation(T_WB_tilted * T_BC, 0.01).Project(points);
    Eigen::Isometry3d T_WC_level = T_WB_level * T_BC;
    T_WC_level.translation() = (T_WB_tilted * T_BC).translation();
    const auto level = testing::FreeCameraSimulation(T_WC_level, 0.01).Project(points);
    const auto derotated = LevelView(tilted, T_WB_tilted.linear(), T_BC.linear());
    ASSERT_TRUE(derotated.has_value());
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_LT(((*derotated)[i] - level[i]).norm(), 1e-12) << i;
      EXPECT_GT((tilted[i] - level[i]).norm(), 0.05) << i;  // the tilt did move the points
    }
  }
}

TEST(LevelViewTest, PointBehindTheLevelCameraAndBadInput) {
  const Eigen::Matrix3d R_BC = testing::ForwardCameraMount().linear();
  // Pitched 80 deg nose down: a point 30 deg below the tilted optical axis is 110 deg below the
  // horizon, behind the level forward camera.
  const Eigen::Matrix3d R_WB =
      Eigen::AngleAxisd(80.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_FALSE(LevelView({Eigen::Vector2d(0.0, std::tan(30.0 * M_PI / 180.0))}, R_WB, R_BC));
  EXPECT_THROW(LevelView({Eigen::Vector2d(NAN, 0.0)}, Eigen::Matrix3d::Identity(), R_BC),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::servo
