// Waypoint selection (seed 003 Sec. III-C, III-D) on synthetic EDT point sets with known answers:
// an open wall is reached without replanning, a trunk on the line of sight forces the next-best
// segment, the result is the exact optimum of the one-hot binary program (every cheaper feasible
// segment was tried and failed its spatial windows), the expanse and collision-threshold
// constraints exclude segments, and back-projection puts patches where the camera sees them.
#include "planning/mono_nav/waypoint_selector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "perception/camera/optical_axes.h"
#include "perception/camera/pinhole_camera.h"

namespace aperture::planning {
namespace {

// A grid of points in the plane x = x_m over y in [y0, y1], z in [z0, z1], 0.1 m apart.
void AddWall(double x_m, double y0, double y1, double z0, double z1,
             std::vector<Eigen::Vector3d>* points) {
  for (double y = y0; y <= y1 + 1e-9; y += 0.1) {
    for (double z = z0; z <= z1 + 1e-9; z += 0.1) points->emplace_back(x_m, y, z);
  }
}

const Eigen::Vector3d kGoalAhead(20.0, 0.0, 0.0);
const Eigen::Vector3d kForward(1.0, 0.0, 0.0);

TEST(WaypointSelector, OpenWallIsReachedWithoutReplanning) {
  std::vector<Eigen::Vector3d> points;
  AddWall(5.0, -2.0, 2.0, -1.0, 1.0, &points);
  const WaypointSelector selector;
  const WaypointSelection selection = selector.Select(points, kForward, kGoalAhead);
  ASSERT_EQ(selection.segments.size(), 1u);
  ASSERT_TRUE(selection.chosen.has_value());
  EXPECT_EQ(selection.Replans(), 0);
  const Segment& wall = selection.segments[0];
  EXPECT_NEAR(wall.centroid_B.x(), 5.0, 1e-9);
  EXPECT_NEAR(wall.rho_m, 0.0, 1e-9);
  // sqrt(3) x the smaller standard deviation: z over 21 grid points 0.1 m apart has variance
  // (21^2 - 1) / 12 * 0.01, so r = 1.049 (~ half the 2 m height).
  EXPECT_NEAR(wall.radius_m, std::sqrt(3.0 * (21.0 * 21.0 - 1.0) / 12.0 * 0.01), 1e-9);
  // The waypoint is on the line of sight, short of the wall; the path ends there.
  EXPECT_NEAR(selection.waypoint_B.y(), 0.0, 1e-9);
  EXPECT_LT(selection.waypoint_B.x(), 5.0 - 0.35);
  EXPECT_TRUE(selection.path_B.back().isApprox(selection.waypoint_B));
  EXPECT_TRUE(selection.path_B.front().isZero());
}

TEST(WaypointSelector, TrunkOnTheLineOfSightForcesTheNextBestSegmentExactly) {
  std::vector<Eigen::Vector3d> points;
  AddWall(2.0, -0.2, 0.2, -1.5, 1.5, &points);   // a trunk 2 m ahead, 0.4 m wide
  AddWall(6.0, -1.2, 1.2, -1.5, 1.5, &points);   // background right behind it
  AddWall(6.0, 2.0, 4.0, -1.5, 1.5, &points);    // background to the left
  AddWall(6.0, -4.5, -2.0, -1.5, 1.5, &points);  // and to the right, wider
  const WaypointSelector selector;
  // From hover (no velocity to be tangent to) the Bezier paths are straight lines.
  const WaypointSelection selection = selector.Select(points, Eigen::Vector3d::Zero(), kGoalAhead);
  ASSERT_EQ(selection.segments.size(), 4u);
  ASSERT_TRUE(selection.chosen.has_value());
  const Segment& chosen = selection.segments[*selection.chosen];
  EXPECT_GT(std::abs(chosen.centroid_B.y()), 1.5) << "a segment beside the trunk";
  EXPECT_GE(selection.Replans(), 1) << "the background behind the trunk was tried first";
  EXPECT_TRUE(selector.PathIsFree(selection.path_B, selection.points_B));
  // Exact optimum of the binary program: every feasible segment cheaper than the chosen one was
  // tried before it (and failed its windows); the chosen one meets both constraints.
  EXPECT_TRUE(chosen.meets_threshold && chosen.meets_expanse);
  for (int i = 0; i < int(selection.segments.size()); ++i) {
    const Segment& s = selection.segments[i];
    if (i == *selection.chosen || !s.meets_threshold || !s.meets_expanse) continue;
    if (s.cost < chosen.cost) {
      EXPECT_NE(std::find(selection.tried.begin(), selection.tried.end(), i),
                selection.tried.end());
    }
  }
  // The trunk is narrower than eta = delta + max(sigma_y, sigma_z): excluded by the expanse.
  for (const Segment& s : selection.segments) {
    if (std::abs(s.centroid_B.x() - 2.0) < 1e-9) {
      EXPECT_FALSE(s.meets_expanse);
    }
  }
}

TEST(WaypointSelector, ExpanseAndThresholdConstraintsExcludeSegments) {
  std::vector<Eigen::Vector3d> points;
  AddWall(6.0, -0.1, 0.1, -0.1, 0.1, &points);  // a tiny far gap on the line of sight: r < eta
  AddWall(0.3, 1.0, 3.0, -1.0, 1.0, &points);   // a wide segment closer than alpha
  AddWall(6.0, 2.0, 5.0, -1.0, 1.0, &points);   // the only feasible one
  const WaypointSelector selector;
  const WaypointSelection selection = selector.Select(points, kForward * 2.0, kGoalAhead);
  ASSERT_EQ(selection.segments.size(), 3u);
  int feasible = 0;
  for (const Segment& s : selection.segments) feasible += s.meets_threshold && s.meets_expanse;
  EXPECT_EQ(feasible, 1);
  ASSERT_TRUE(selection.chosen.has_value());
  EXPECT_NEAR(selection.segments[*selection.chosen].centroid_B.y(), 3.5, 1e-6);
  // alpha = v t_t = 2 m/s * 0.3 s = 0.6 m > 0.3 m.
  for (const Segment& s : selection.segments) {
    if (s.distance_m < 0.5) {
      EXPECT_FALSE(s.meets_threshold);
    }
    if (s.radius_m < 0.35) {
      EXPECT_FALSE(s.meets_expanse);
    }
  }
}

TEST(WaypointSelector, RandomOrderIsSeededAndOnlyAcceptsFreePaths) {
  std::vector<Eigen::Vector3d> points;
  AddWall(2.0, -0.2, 0.2, -1.5, 1.5, &points);
  AddWall(6.0, -1.2, 1.2, -1.5, 1.5, &points);
  AddWall(6.0, -4.5, -2.0, -1.5, 1.5, &points);
  const WaypointSelector selector;
  std::set<int> first_tried;
  for (std::uint64_t seed = 0; seed < 12; ++seed) {
    const WaypointSelection random =
        selector.Select(points, kForward, kGoalAhead, WaypointOrder::kRandom, seed);
    ASSERT_TRUE(random.chosen.has_value());
    EXPECT_TRUE(selector.PathIsFree(random.path_B, random.points_B));
    EXPECT_EQ(random.tried.back(), *random.chosen);
    first_tried.insert(random.tried.front());
    // Same seed, same order.
    EXPECT_EQ(selector.Select(points, kForward, kGoalAhead, WaypointOrder::kRandom, seed).tried,
              random.tried);
  }
  EXPECT_GE(first_tried.size(), 2u);
}

TEST(WaypointSelector, WaypointHeightIsClampedToTheGoalsAndWindowsCheckTheGivenObstacles) {
  // One wide wall 5 m ahead whose centroid is 1 m above the goal's height (sky-heavy segment).
  std::vector<Eigen::Vector3d> points;
  AddWall(5.0, -2.0, 2.0, 0.0, 2.0, &points);
  WaypointSelectorParams params;
  params.max_height_from_goal_m = 0.2;
  const WaypointSelector selector(params);
  const WaypointSelection clamped = selector.Select(points, kForward, kGoalAhead);
  ASSERT_TRUE(clamped.chosen.has_value());
  EXPECT_NEAR(clamped.waypoint_B.z(), 0.2, 1e-12);  // centroid z ~1 m, goal z 0
  const WaypointSelection free_3d = WaypointSelector().Select(points, kForward, kGoalAhead);
  ASSERT_TRUE(free_3d.chosen.has_value());
  EXPECT_GT(free_3d.waypoint_B.z(), 0.5);  // the paper's waypoint follows the centroid up
  // A metric obstacle 2 m ahead on the (level) path, absent from the clustered points: the path is
  // rejected when the windows check it, accepted when they check the clustered points only.
  const std::vector<Eigen::Vector3d> obstacles{Eigen::Vector3d(2.0, 0.0, 0.1)};
  EXPECT_FALSE(selector.Select(points, kForward, kGoalAhead, WaypointOrder::kOptimal, 0, &obstacles)
                   .chosen.has_value());
  EXPECT_THROW(
      [] {
        WaypointSelectorParams bad;
        bad.max_height_from_goal_m = -1.0;
        WaypointSelector{bad};
      }(),
      std::invalid_argument);
}

// A straight path from the vehicle to `end`, 0.1 m between samples.
std::vector<Eigen::Vector3d> StraightPath(const Eigen::Vector3d& end) {
  std::vector<Eigen::Vector3d> path;
  const int n = static_cast<int>(std::ceil(end.norm() / 0.1));
  for (int k = 0; k <= n; ++k) path.push_back(end * (double(k) / n));
  return path;
}

TEST(WaypointSelector, PathsRunOnlyThroughSeenSpace) {
  // Nothing was seen anywhere: only the field of view (+-45 deg) says where a path may go.
  const std::vector<Eigen::Vector3d> no_points;
  WaypointSelectorParams params;
  params.max_bearing_rad = M_PI / 4.0;
  const WaypointSelector selector(params);
  const double bearing_55 = -55.0 * M_PI / 180.0, bearing_20 = 20.0 * M_PI / 180.0;
  const Eigen::Vector3d at_55(3.0 * std::cos(bearing_55), 3.0 * std::sin(bearing_55), 0.0);
  const Eigen::Vector3d at_20(3.0 * std::cos(bearing_20), 3.0 * std::sin(bearing_20), 0.0);
  EXPECT_FALSE(selector.PathIsFree(StraightPath(at_55), no_points));           // beside the view
  EXPECT_TRUE(WaypointSelector().PathIsFree(StraightPath(at_55), no_points));  // no check
  EXPECT_TRUE(selector.PathIsFree(StraightPath(at_20), no_points));
  // The vehicle's half width counts: a sample 4 m ahead is seen up to |y| = 4 - 0.25 m.
  EXPECT_TRUE(selector.IsSeen(Eigen::Vector3d(4.0, 3.74, 0.0)));
  EXPECT_FALSE(selector.IsSeen(Eigen::Vector3d(4.0, -3.76, 0.0)));
  // Within seen_from_m (1 m) is where the vehicle is and was: not checked.
  EXPECT_TRUE(selector.IsSeen(Eigen::Vector3d(0.0, 0.9, 0.0)));
  EXPECT_FALSE(selector.IsSeen(Eigen::Vector3d(0.0, 1.1, 0.0)));
  EXPECT_FALSE(selector.IsSeen(Eigen::Vector3d(-2.0, 0.0, 0.0)));  // behind
  // Select only returns paths through seen space: a segment 60 deg to the side is not taken.
  std::vector<Eigen::Vector3d> side;
  AddWall(3.0, -6.0, -4.5, -1.0, 1.0, &side);
  EXPECT_TRUE(
      WaypointSelector().Select(side, Eigen::Vector3d::Zero(), kGoalAhead).chosen.has_value());
  EXPECT_FALSE(selector.Select(side, Eigen::Vector3d::Zero(), kGoalAhead).chosen.has_value());
  EXPECT_THROW(
      [] {
        WaypointSelectorParams bad;
        bad.max_bearing_rad = 0.0;
        WaypointSelector{bad};
      }(),
      std::invalid_argument);
}

TEST(WaypointSelector, ExtensionTowardsTheGoalStandsOffFromTheFirstObstacle) {
  // A trunk 4 m ahead on the line to the goal; the path so far ends 1 m ahead.
  std::vector<Eigen::Vector3d> trunk;
  AddWall(4.0, -0.2, 0.2, -1.0, 1.0, &trunk);
  const WaypointSelector selector;
  const std::vector<Eigen::Vector3d> start{Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0, 0)};
  // Samples 0.2 m apart: 3.6 m is the last whose window (0.35 m) misses the trunk, 3.8 m is
  // blocked; a 1.5 m standoff from it keeps the samples up to 2.2 m (3.8 - 2.4 < 1.5).
  std::vector<Eigen::Vector3d> path = start;
  selector.ExtendTowardsGoal(kGoalAhead, trunk, 4.0, 1.5, &path);
  EXPECT_NEAR(path.back().x(), 2.2, 1e-9);
  EXPECT_GE(3.8 - path.back().x(), 1.5);
  EXPECT_TRUE(selector.PathIsFree(path, trunk));
  path = start;
  selector.ExtendTowardsGoal(kGoalAhead, trunk, 4.0, 0.0, &path);
  EXPECT_NEAR(path.back().x(), 3.6, 1e-9);  // no standoff: up to the trunk's window
  // Nothing in the way: the full 4 m; the standoff never removes the path it was given.
  path = start;
  selector.ExtendTowardsGoal(kGoalAhead, {}, 4.0, 1.5, &path);
  EXPECT_NEAR(path.back().x(), 5.0, 1e-9);
  std::vector<Eigen::Vector3d> blocked_at_once{Eigen::Vector3d::Zero(), Eigen::Vector3d(3.5, 0, 0)};
  selector.ExtendTowardsGoal(kGoalAhead, trunk, 4.0, 1.5, &blocked_at_once);
  EXPECT_EQ(blocked_at_once.size(), 2u);
  // Unseen space ends the extension without a standoff (no obstacle was seen there): towards a
  // goal straight to the right of the path's end (1, 0, 0), y = -0.6 m is the last sample whose
  // half width lies in the +-45 deg view (atan2(0.6 + 0.25, 1) = 40 deg; -0.8 m: 46 deg).
  WaypointSelectorParams narrow;
  narrow.max_bearing_rad = M_PI / 4.0;
  path = start;
  WaypointSelector(narrow).ExtendTowardsGoal(Eigen::Vector3d(1.0, -20.0, 0.0), {}, 4.0, 1.5, &path);
  EXPECT_NEAR(path.back().y(), -0.6, 1e-9);
}

TEST(WaypointSelector, BackProjectionPutsPatchesAlongTheirRays) {
  // 90 deg pinhole, 64 x 48 px, 8 px patches; camera looking along x_B (T_BC: z_C = x_B,
  // x_C = -y_B, y_C = -z_B).
  const perception::PinholeCamera camera(64, 48,
                                         perception::PinholeIntrinsics{32.0, 32.0, 31.5, 23.5});
  const Eigen::Matrix3d R_BC = perception::OpticalAxesAlongX();
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  T_BC.linear() = R_BC;
  cv::Mat d_eff(6, 8, CV_32F, cv::Scalar(4.0f));
  d_eff.at<float>(0, 0) = -1.0f;  // imminent: left out
  const std::vector<Eigen::Vector3d> points =
      BackProjectGrid(d_eff, Eigen::Vector2d(8.0, 8.0), camera, T_BC);
  ASSERT_EQ(points.size(), 47u);
  for (const Eigen::Vector3d& p : points) EXPECT_NEAR(p.x(), 4.0, 1e-9);  // z-depth = x_B
  // Patch (row 3, col 4) centre is pixel (35.5, 27.5): 4 px right of and 4 px below the centre.
  const Eigen::Vector3d& p = points[3 * 8 + 4 - 1];
  EXPECT_NEAR(p.y(), -4.0 * 4.0 / 32.0, 1e-9);
  EXPECT_NEAR(p.z(), -4.0 * 4.0 / 32.0, 1e-9);
}

}  // namespace
}  // namespace aperture::planning
