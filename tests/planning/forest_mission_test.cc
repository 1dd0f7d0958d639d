// ForestMission's heading and seen space (beyond seed 003's fixed psi = 0): the heading reference
// turns towards the goal at the configured yaw rate and then holds it, and the selector's field of
// view is the camera's. Closed-loop flights are tests/experiments/forest_flight_sitl_test.cc.
#include "planning/mono_nav/forest_mission.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "perception/camera/pinhole_camera.h"

namespace aperture::planning {
namespace {

// A 90 deg, 640 x 480 pinhole looking along x_B (z_C = x_B, x_C = -y_B, y_C = -z_B).
Eigen::Isometry3d ForwardMount() {
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return T_BC;
}

TEST(ForestMission, HeadingTurnsTowardsTheGoalAtTheYawRateLimit) {
  const control::VehicleParameters vehicle;
  const auto camera = std::make_shared<perception::PinholeCamera>(
      640, 480, perception::PinholeIntrinsics{320.0, 320.0, 319.5, 239.5});
  ForestMissionParams params;
  params.goal_W = Eigen::Vector3d(0.0, 10.0, 1.5);  // 90 deg to the left of the start heading
  params.max_yaw_rate_radps = 0.5;
  ForestMission mission(params, camera, ForwardMount(), vehicle, perception::DefaultMonoDepthModel());
  // The selector's field of view is the camera's: +-45 deg.
  EXPECT_NEAR(mission.selector_params().max_bearing_rad, M_PI / 4.0, 1e-3);

  // Hovering at (0, 0, 1.5), level, heading 0: IMU at 200 Hz, odometry at 50 Hz, Step at 100 Hz.
  perception::PoseMeasurement pose;
  pose.p_WX = Eigen::Vector3d(0.0, 0.0, 1.5);
  pose.covariance = 1e-4 * perception::Matrix6d::Identity();
  double heading_at_1s = 0.0;
  for (int k = 0; k <= 1000; ++k) {  // 5 s
    const double t = 0.005 * k;
    mission.OnImu({t, Eigen::Vector3d(0.0, 0.0, vehicle.gravity_mps2), Eigen::Vector3d::Zero()});
    if (k % 4 == 0) {
      pose.t_s = t;
      mission.OnOdometry(pose);
    }
    if (k % 2 == 0) mission.Step(t);
    if (k == 200) heading_at_1s = mission.heading_rad();
  }
  // The first Step fixes the start heading (0); 1 s later it has turned 0.5 rad (one 10 ms step
  // of the rate limit either side: the turn starts at the first Step with an estimate).
  EXPECT_NEAR(heading_at_1s, 0.5, 0.5 * 0.011);
  EXPECT_NEAR(mission.heading_rad(), M_PI / 2.0, 1e-9);  // reached after ~3.1 s, then held

  // A zero yaw rate keeps the start heading (the paper's psi = 0).
  params.max_yaw_rate_radps = 0.0;
  ForestMission fixed(params, camera, ForwardMount(), vehicle, perception::DefaultMonoDepthModel());
  pose.t_s = 0.0;
  fixed.OnImu({0.0, Eigen::Vector3d(0.0, 0.0, vehicle.gravity_mps2), Eigen::Vector3d::Zero()});
  fixed.OnOdometry(pose);
  for (int k = 0; k < 100; ++k) {
    fixed.OnImu({0.01 * (k + 1), Eigen::Vector3d(0.0, 0.0, vehicle.gravity_mps2),
                 Eigen::Vector3d::Zero()});
    fixed.Step(0.01 * (k + 1));
  }
  EXPECT_EQ(fixed.heading_rad(), 0.0);

  params.max_yaw_rate_radps = -1.0;
  EXPECT_THROW(ForestMission(params, camera, ForwardMount(), vehicle,
                             perception::DefaultMonoDepthModel()),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::planning
