// ForestMission beyond seed 003: the heading reference (the paper keeps psi = 0) turns towards the
// goal at rest and towards the direction of travel in flight, at the configured yaw rate; the
// selector's field of view is the camera's; a vehicle stalled without a path backs off along the
// path it flew, or looks aside where it has flown none. Closed-loop flights are
// tests/experiments/forest_flight_sitl_test.cc.
#include "planning/mono_nav/forest_mission.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <opencv2/core.hpp>

#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"

namespace aperture::planning {
namespace {

// A 90 deg, 640 x 480 pinhole looking along x_B (z_C = x_B, x_C = -y_B, y_C = -z_B).
Eigen::Isometry3d ForwardMount() {
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() = perception::OpticalAxesAlongX();
  return T_BC;
}

TEST(ForestMission, HeadingTurnsTowardsTheGoalAtTheYawRateLimit) {
  const control::VehicleParameters vehicle;
  const auto camera = std::make_shared<perception::PinholeCamera>(
      640, 480, perception::PinholeIntrinsics{320.0, 320.0, 319.5, 239.5});
  ForestMissionParams params;
  params.goal_W = Eigen::Vector3d(0.0, 10.0, 1.5);  // 90 deg to the left of the start heading
  params.max_yaw_rate_radps = 0.5;
  ForestMission mission(params, camera, ForwardMount(), vehicle,
                        perception::DefaultMonoDepthModel());
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
    fixed.OnImu(
        {0.01 * (k + 1), Eigen::Vector3d(0.0, 0.0, vehicle.gravity_mps2), Eigen::Vector3d::Zero()});
    fixed.Step(0.01 * (k + 1));
  }
  EXPECT_EQ(fixed.heading_rad(), 0.0);

  params.max_yaw_rate_radps = -1.0;
  EXPECT_THROW(
      ForestMission(params, camera, ForwardMount(), vehicle, perception::DefaultMonoDepthModel()),
      std::invalid_argument);
}

TEST(ForestHeadingTarget, TowardsTheGoalButInFlightNoFartherThanTheLimitFromTheTravel) {
  const Eigen::Vector3d goal_W(22.0, 0.0, 1.5);
  const double limit_rad = 0.5;
  // Layout 21 before the fix: 3.5 m from the goal, the goal 44 deg to the left, a spline planned
  // earlier flying 1.5 m/s at -34 deg. The heading turns towards the goal only until the travel
  // is limit_rad off it (the camera's half field of view is 45 deg).
  const Eigen::Vector3d p_W(19.5, -2.43, 1.5);
  const double goal_rad = std::atan2(2.43, 2.5);
  const double travel_rad = -34.0 * M_PI / 180.0;
  const Eigen::Vector3d v_W = 1.5 * Eigen::Vector3d(std::cos(travel_rad), std::sin(travel_rad), 0);
  const auto target = [&](const Eigen::Vector3d& v, std::optional<double> look_aside,
                          bool backing_off) {
    return ForestHeadingTarget(p_W, goal_W, v, 0.3, limit_rad, look_aside, backing_off);
  };
  EXPECT_NEAR(*target(v_W, std::nullopt, false), travel_rad + limit_rad, 1e-12);
  // Travel within the limit of the goal: the goal's bearing.
  const double near_rad = goal_rad - 0.3;
  EXPECT_NEAR(
      *target(Eigen::Vector3d(std::cos(near_rad), std::sin(near_rad), 0), std::nullopt, false),
      goal_rad, 1e-12);
  // Across +-pi: the travel at 170 deg, the goal behind at -135 deg (75 deg away, the short way).
  const Eigen::Vector3d behind_W = goal_W + Eigen::Vector3d(5.0, 5.0, 0.0);
  EXPECT_NEAR(
      *ForestHeadingTarget(behind_W, goal_W, Eigen::Vector3d(std::cos(3.0), std::sin(3.0), 0.0),
                           0.3, limit_rad, std::nullopt, false),
      std::remainder(3.0 + limit_rad, 2.0 * M_PI), 1e-12);
  // At rest (or slower than the threshold horizontally; a climb does not count): the goal.
  EXPECT_NEAR(*target(0.15 * v_W, std::nullopt, false), goal_rad, 1e-12);
  EXPECT_NEAR(*target(Eigen::Vector3d(0, 0, 1), std::nullopt, false), goal_rad, 1e-12);
  // A look-aside wins at rest, not in flight.
  EXPECT_EQ(*target(Eigen::Vector3d::Zero(), 0.7, false), 0.7);
  EXPECT_NEAR(*target(v_W, 0.7, false), travel_rad + limit_rad, 1e-12);
  // Backing off (flying backwards) and near the goal: hold.
  EXPECT_FALSE(target(-v_W, std::nullopt, true));
  EXPECT_FALSE(ForestHeadingTarget(Eigen::Vector3d(21.3, 0.5, 1.5), goal_W, v_W, 0.3, limit_rad,
                                   std::nullopt, false));
}

TEST(GoalLeftTheView, WhenNoHeadingTheRuleAllowsShowsTheGoal) {
  // The stall course with the torque observer: passing the trunk wide (y ~ 3 m) at 0.5 m/s
  // heading ~5 deg, the goal 6 m ahead of the start falls behind. With a 0.5 rad heading limit
  // and a 45 deg seen wedge, the goal leaves the view beyond 73.6 deg off the travel.
  const Eigen::Vector3d goal_W(6.0, 0.0, 1.5);
  const double limit_rad = 0.5;
  const double wedge_rad = M_PI / 4.0;
  const auto left = [&](const Eigen::Vector3d& p_W, double travel_deg, double speed_mps) {
    const double travel_rad = travel_deg * M_PI / 180.0;
    const Eigen::Vector3d v_W =
        speed_mps * Eigen::Vector3d(std::cos(travel_rad), std::sin(travel_rad), 0.0);
    return GoalLeftTheView(p_W, goal_W, v_W, 0.3, limit_rad, wedge_rad);
  };
  // The goal 72.2 deg right of the travel (at 12.2 s): still within 28.6 + 45 deg.
  EXPECT_FALSE(left(Eigen::Vector3d(4.49, 2.87, 1.5), 10.0, 0.5));
  // 75.9 deg (at 13.2 s): left the view.
  EXPECT_TRUE(left(Eigen::Vector3d(5.0, 2.93, 1.5), 4.7, 0.5));
  // The other side, across +-pi: travel at 170 deg, the goal at -100 deg (90 deg to the left).
  EXPECT_TRUE(left(goal_W + Eigen::Vector3d(0.5, 2.84, 0.0), 170.0, 0.5));
  EXPECT_FALSE(left(goal_W + Eigen::Vector3d(2.0, 0.35, 0.0), 170.0, 0.5));  // 20 deg off
  // Slow (a look-aside at rest turns the camera off the goal on purpose) or near the goal (its
  // bearing swings): never.
  EXPECT_FALSE(left(Eigen::Vector3d(5.0, 2.93, 1.5), 4.7, 0.25));
  EXPECT_FALSE(left(goal_W + Eigen::Vector3d(-0.2, 0.9, 0.0), 0.0, 0.5));
}

// Feeds a mission IMU samples (200 Hz), odometry poses (50 Hz), Step (100 Hz) and black frames
// (10 Hz: no depth the planner can pass) for a vehicle at p_W(t), level, heading 0, until t_end_s.
class StalledMission : public ::testing::Test {
 protected:
  StalledMission()
      : camera_(std::make_shared<perception::PinholeCamera>(
            640, 480, perception::PinholeIntrinsics{320.0, 320.0, 319.5, 239.5})) {
    params_.goal_W = Eigen::Vector3d(10.0, 0.0, 1.5);
    params_.max_yaw_rate_radps = 0.5;
    // Segments of single patches: none passes the expanse constraint (no path, as the black
    // frames alone would give), and the clustering of the dense map stays cheap.
    params_.waypoints.cluster_tolerance_m = 0.01;
    params_.waypoints.min_cluster_points = 1;
    params_.recovery_look_aside_rad = 0.6;  // short turns keep the test short
  }
  // x(t) = the start + length_m (3 s^2 - 2 s^3), s = t / move_s (then at rest), along x_W.
  void Fly(ForestMission* mission, double t_begin_s, double t_end_s, double length_m = 0.0,
           double move_s = 1.0) {
    perception::PoseMeasurement pose;
    pose.covariance = 1e-4 * perception::Matrix6d::Identity();
    const cv::Mat black = cv::Mat::zeros(480, 640, CV_8UC3);
    for (int k = int(std::lround(t_begin_s / 0.005)); k * 0.005 <= t_end_s + 1e-9; ++k) {
      const double t = 0.005 * k;
      const double s = std::min(t / move_s, 1.0);
      const double a = s < 1.0 ? length_m * (6.0 - 12.0 * s) / (move_s * move_s) : 0.0;
      mission->OnImu({t, Eigen::Vector3d(a, 0.0, vehicle_.gravity_mps2), Eigen::Vector3d::Zero()});
      if (k % 4 == 0) {
        pose.t_s = t;
        pose.p_WX = Eigen::Vector3d(length_m * s * s * (3.0 - 2.0 * s), 0.0, 1.5);
        mission->OnOdometry(pose);
      }
      if (k % 2 == 0) mission->Step(t);
      if (k % 20 == 10) mission->OnFrame({t, 0, k / 20, black, {}});
    }
  }
  const control::VehicleParameters vehicle_;
  std::shared_ptr<perception::PinholeCamera> camera_;
  ForestMissionParams params_;
};

TEST_F(StalledMission, AtTheStartItLooksToOneSideOfTheGoalThenToTheOther) {
  ForestMission mission(params_, camera_, ForwardMount(), vehicle_,
                        perception::DefaultMonoDepthModel());
  Fly(&mission, 0.0, 0.95);
  EXPECT_EQ(mission.frames_without_path(), int(mission.frames().size()));
  EXPECT_EQ(mission.back_offs() + mission.look_asides(), 0);  // < recovery_after_s = 1 s at rest
  // At 1.05 s: nothing flown to back off along, so the heading turns 0.6 rad left at 0.5 rad/s
  // (1.2 s), rests 1 s, then turns 1.2 rad right (2.4 s).
  Fly(&mission, 1.0, 2.5);
  EXPECT_EQ(mission.look_asides(), 1);
  EXPECT_EQ(mission.back_offs(), 0);
  EXPECT_NEAR(mission.heading_rad(), 0.6, 1e-9);
  Fly(&mission, 2.505, 6.0);
  EXPECT_EQ(mission.look_asides(), 2);
  EXPECT_NEAR(mission.heading_rad(), -0.6, 1e-9);
  EXPECT_EQ(mission.frames_without_path(), int(mission.frames().size()));
  // Every frame ran the selector (the goal is 10 m away: no direct path); no segment met the
  // expanse constraint, so none was tried and none rejected.
  EXPECT_EQ(mission.selections(), int(mission.frames().size()));
  EXPECT_EQ(mission.replans(), 0);
  EXPECT_EQ(mission.frames_replanned(), 0);

  // No recovery (recovery_after_s = 1e9): the heading stays on the goal.
  params_.recovery_after_s = 1e9;
  ForestMission none(params_, camera_, ForwardMount(), vehicle_,
                     perception::DefaultMonoDepthModel());
  Fly(&none, 0.0, 3.0);
  EXPECT_EQ(none.back_offs() + none.look_asides(), 0);
  EXPECT_NEAR(none.heading_rad(), 0.0, 1e-9);
}

TEST_F(StalledMission, AfterFlyingItBacksOffAlongTheFlownPath) {
  ForestMission mission(params_, camera_, ForwardMount(), vehicle_,
                        perception::DefaultMonoDepthModel());
  // 1.5 m forward in 1.5 s, then at rest without a path.
  Fly(&mission, 0.0, 2.45, 1.5, 1.5);
  EXPECT_EQ(mission.back_offs() + mission.look_asides(), 0);
  ASSERT_GE(mission.trail().points_W().size(), 14u);  // ~0.1 m apart
  EXPECT_NEAR(mission.trail().points_W().back().x(), 1.5, 0.1);
  Fly(&mission, 2.5, 2.7, 1.5, 1.5);
  // 1 s at rest: a spline back along the trail (recovery_backoff_m = 1 m), heading held.
  ASSERT_EQ(mission.back_offs(), 1);
  EXPECT_EQ(mission.look_asides(), 0);
  EXPECT_NEAR(mission.trail().points_W().back().x(), 0.5, 0.1);
  EXPECT_EQ(mission.heading_rad(), 0.0);
  // The mission commands the back-off: the reference accelerates towards -x. (The vehicle here
  // does not move, so the spline flies on; the hold is not a map: no further recovery meanwhile.)
  Fly(&mission, 2.705, 4.0, 1.5, 1.5);
  EXPECT_EQ(mission.back_offs() + mission.look_asides(), 1);
  EXPECT_EQ(mission.heading_rad(), 0.0);
}

}  // namespace
}  // namespace aperture::planning
