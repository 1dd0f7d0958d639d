// The execution timeline of a planned ground-robot mission (ground_mission_timeline.h): it lasts
// exactly the planner's mission cost, starts at the scene's pose, ends facing the goal with every
// removed obstacle on its place, moves nothing faster than the robot can (nothing jumps), keeps
// a carried obstacle on the robot and keeps the robot clear of the obstacles at every sample.
#include "planning/ground_mission/ground_mission_timeline.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "control/constants.h"
#include "planning/ground_mission/random_mission_scene.h"
#include "tests/support/paper_mission_scenes.h"

namespace aperture::planning {
namespace {

using control::kDegToRad;
using control::kPi;

double AngleBetween(double a_rad, double b_rad) {
  return std::abs(std::remainder(a_rad - b_rad, 2.0 * kPi));
}

// What the timeline promises for `mission`, sampled every dt_s. Counts the removals carried back.
void ExpectTimelineFollowsMission(const GroundMissionScene& scene,
                                  const GroundMissionParams& params, const GroundMission& mission,
                                  int* backward_carries = nullptr) {
  const GroundMissionTimeline timeline(mission, scene, params);
  const double duration_s = timeline.duration_s();
  ASSERT_NEAR(duration_s, mission.cost_s, 1e-9 * mission.cost_s) << mission;
  const double half_diagonal_m = params.cell_size_m * std::sqrt(2.0) / 2;
  ASSERT_LE(timeline.start_offset_W().norm(), half_diagonal_m + 1e-12);

  // The start: the scene's pose, the obstacles where the scene has them.
  const GroundRobotSample start = timeline.Sample(0.0);
  EXPECT_LT((start.robot_p_W - scene.robot_p_W).norm(), 1e-12);
  EXPECT_LT(AngleBetween(start.robot_yaw_rad, scene.robot_yaw_rad), 1e-12);
  EXPECT_EQ(start.carried, -1);
  EXPECT_EQ(start.leg, 0);
  ASSERT_EQ(start.movable_p_W.size(), scene.movable_obstacles.size());
  for (size_t k = 0; k < scene.movable_obstacles.size(); ++k) {
    EXPECT_EQ(start.movable_p_W[k], scene.movable_obstacles[k].p_W);
    EXPECT_EQ(start.movable_yaw_rad[k], scene.movable_obstacles[k].yaw_rad);
  }
  EXPECT_EQ(timeline.Sample(-5.0).robot_p_W, start.robot_p_W);

  // The end: at the last waypoint (to the open-loop start offset), facing the goal, every
  // removed obstacle on its place with its own yaw, the others untouched.
  const GroundRobotSample end = timeline.Sample(duration_s);
  const GroundWaypoint& last = mission.legs.back().waypoints.back();
  EXPECT_EQ(end.activity, "done");
  EXPECT_EQ(end.leg, static_cast<int>(mission.legs.size()) - 1);
  EXPECT_EQ(end.carried, -1);
  EXPECT_LE((end.robot_p_W - last.p_W).norm(), half_diagonal_m + 1e-9);
  EXPECT_LT(AngleBetween(end.robot_yaw_rad, last.yaw_rad), 1e-12);
  EXPECT_EQ(timeline.Sample(duration_s + 10.0).robot_p_W, end.robot_p_W);
  std::vector<bool> removed(scene.movable_obstacles.size(), false);
  for (const GroundObstacleRemoval& removal : mission.removals) {
    const size_t k = static_cast<size_t>(removal.obstacle);
    removed[k] = true;
    EXPECT_EQ(end.movable_p_W[k], removal.place_p_W);
    EXPECT_LT(AngleBetween(end.movable_yaw_rad[k], scene.movable_obstacles[k].yaw_rad), 1e-12);
  }
  for (size_t k = 0; k < scene.movable_obstacles.size(); ++k) {
    if (!removed[k]) {
      EXPECT_EQ(end.movable_p_W[k], scene.movable_obstacles[k].p_W);
    }
  }

  // Grasp and place times: remove_time_s split in halves; a removal carried back reverses and
  // returns at the driving speed, 2 x backward_m / speed in all, as the planner counts.
  const double speed_mps = params.driving_speed_mps;
  const double handle_s = params.remove_time_s / 2;
  ASSERT_EQ(timeline.removal_times().size(), mission.removals.size());
  for (size_t r = 0; r < mission.removals.size(); ++r) {
    const GroundObstacleRemoval& removal = mission.removals[r];
    const GroundRemovalTimes& times = timeline.removal_times()[r];
    EXPECT_EQ(times.obstacle, removal.obstacle);
    EXPECT_NEAR(times.grasp_end_s - times.grasp_start_s, handle_s, 1e-9);
    EXPECT_NEAR(times.place_end_s - times.place_start_s, handle_s, 1e-9);
    const GroundRobotSample grasping = timeline.Sample(times.grasp_start_s);
    EXPECT_LT((grasping.robot_p_W - removal.grasp_p_W - timeline.start_offset_W()).norm(), 1e-9);
    const GroundRobotSample placing = timeline.Sample(times.place_start_s);
    EXPECT_LT((placing.robot_p_W - removal.robot_at_place_p_W - timeline.start_offset_W()).norm(),
              1e-9);
    if (removal.backward_m > 0.0) {
      if (backward_carries) ++*backward_carries;
      EXPECT_NEAR(times.place_start_s - times.grasp_end_s, removal.backward_m / speed_mps, 1e-9);
      const GroundRobotSample reversing =
          timeline.Sample((times.grasp_end_s + times.place_start_s) / 2);
      EXPECT_EQ(reversing.activity, "back");
      EXPECT_EQ(reversing.carried, removal.obstacle);
      // Reversing without turning: the heading of the grasp.
      EXPECT_LT(AngleBetween(reversing.robot_yaw_rad, grasping.robot_yaw_rad), 1e-12);
      // Back at the grasp location after driving the same distance forward.
      const double returned_s = times.place_end_s + removal.backward_m / speed_mps;
      const GroundRobotSample returned = timeline.Sample(returned_s);
      EXPECT_LT((returned.robot_p_W - grasping.robot_p_W).norm(), 1e-9);
      EXPECT_EQ(timeline.Sample(returned_s - 1e-6).activity, "drive");
    } else {
      EXPECT_GE(times.place_start_s, times.grasp_end_s);
    }
  }

  // Every sample: bounded speeds (nothing jumps), the carried obstacle on the robot, the robot
  // clear of the fixed obstacles, the border and the obstacles not in the gripper. The clearance
  // tolerance: the grid checks cell centres only (one cell, see ground_mission_checks.h), and
  // the open-loop path is shifted by the start offset (half a cell diagonal).
  const double turn_rate_rad_s = params.turn_rate_deg_s * kDegToRad;
  const double carry_speed_mps =
      std::max(speed_mps, (params.grasp_radius_m + 2 * half_diagonal_m) / handle_s);
  const double tolerance_m = params.cell_size_m + half_diagonal_m;
  const std::set<std::string> activities{"turn", "drive", "grasp", "back", "place", "done"};
  const double dt_s = 0.05;
  const int steps = static_cast<int>(std::ceil(duration_s / dt_s));
  GroundRobotSample previous = start;
  std::set<std::string> seen;
  for (int i = 1; i <= steps; ++i) {
    const double t_s = std::min(i * dt_s, duration_s);
    const double step_s = t_s - std::min((i - 1) * dt_s, duration_s);
    const GroundRobotSample sample = timeline.Sample(t_s);
    seen.insert(sample.activity);
    ASSERT_EQ(activities.count(sample.activity), 1u) << sample.activity;
    ASSERT_LE((sample.robot_p_W - previous.robot_p_W).norm(), speed_mps * step_s + 1e-9)
        << "t " << t_s << " s: " << mission;
    ASSERT_LE(AngleBetween(sample.robot_yaw_rad, previous.robot_yaw_rad),
              turn_rate_rad_s * step_s + 1e-9)
        << "t " << t_s << " s";
    ASSERT_GE(sample.leg, previous.leg);
    const Eigen::Vector2d& p = sample.robot_p_W;
    ASSERT_TRUE(((p - scene.area_min_W).array() > params.robot_radius_m - tolerance_m).all() &&
                ((scene.area_max_W - p).array() > params.robot_radius_m - tolerance_m).all())
        << "t " << t_s << " s: the robot leaves the field";
    for (const GroundBox& box : scene.fixed_obstacles) {
      ASSERT_GT(DistanceToBox(box, p), params.robot_radius_m - tolerance_m)
          << "t " << t_s << " s: the robot hits a fixed obstacle: " << mission;
    }
    for (size_t k = 0; k < scene.movable_obstacles.size(); ++k) {
      ASSERT_LE((sample.movable_p_W[k] - previous.movable_p_W[k]).norm(),
                carry_speed_mps * step_s + 1e-9)
          << "t " << t_s << " s: obstacle " << k << " jumps";
      const double radius_m = CircumscribedRadius(scene.movable_obstacles[k]);
      if (static_cast<int>(k) == sample.carried) {
        if (sample.activity != "grasp" && sample.activity != "place") {
          ASSERT_EQ(sample.movable_p_W[k], p) << "t " << t_s << " s";
          ASSERT_EQ(sample.movable_yaw_rad[k], sample.robot_yaw_rad) << "t " << t_s << " s";
        }
        continue;
      }
      ASSERT_GT((sample.movable_p_W[k] - p).norm(), radius_m + params.robot_radius_m - tolerance_m)
          << "t " << t_s << " s: the robot hits obstacle " << k << ": " << mission;
    }
    if (sample.activity == "grasp" || sample.activity == "place" || sample.activity == "back") {
      ASSERT_GE(sample.carried, 0) << "t " << t_s << " s";
    }
    previous = sample;
  }
  // Every grasp and place lasts remove_time_s / 2 >= 7.5 s at the D.7 defaults: sampled.
  if (!mission.removals.empty() && handle_s > dt_s) {
    EXPECT_EQ(seen.count("grasp"), 1u);
    EXPECT_EQ(seen.count("place"), 1u);
  }
}

TEST(GroundMissionTimelineTest, FollowsThePaperMissions) {
  const GroundMissionParams params;
  int backward_carries = 0;
  for (const GroundMissionScene& scene :
       {testing::Figure9aScene(), testing::Figure9bScene(), testing::Figure10Scene()}) {
    const GroundMission mission = GroundMissionPlanner(scene, params).Plan();
    ASSERT_TRUE(mission.solved()) << mission;
    ExpectTimelineFollowsMission(scene, params, mission, &backward_carries);
  }
  // D.9b carries its first cube back, D.10 its first two.
  EXPECT_EQ(backward_carries, 3);
}

// >= 100 solved random scenes: the slalom field of the planner's evaluation (2-10 cubes) and the
// small passage field (4-8 cubes around its passage), where most missions remove cubes and the
// crowded ones carry some back.
TEST(GroundMissionTimelineTest, FollowsRandomMissions) {
  const GroundMissionParams params;
  int solved = 0;
  int removals = 0;
  int backward_carries = 0;
  for (std::uint64_t seed = 1; seed <= 120; ++seed) {
    RandomMissionSceneParams scene_params;
    if (seed % 2 == 0) {
      scene_params.field = SlalomField();
      scene_params.movable_obstacles = 2 * (1 + static_cast<int>(seed / 2 % 5));
    } else {
      scene_params.field = PassageField();
      scene_params.movable_obstacles = 4 + static_cast<int>(seed / 2 % 5);
      std::tie(scene_params.region_min_W, scene_params.region_max_W) = PassageRegion();
    }
    const GroundMissionScene scene = RandomMissionScene(scene_params, seed);
    const GroundMission mission = GroundMissionPlanner(scene, params).Plan();
    if (!mission.solved()) continue;
    ++solved;
    removals += static_cast<int>(mission.removals.size());
    SCOPED_TRACE("seed " + std::to_string(seed));
    ExpectTimelineFollowsMission(scene, params, mission, &backward_carries);
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GE(solved, 100);
  EXPECT_GE(removals, 50);
  // 120 solved, 205 removals, 4 of them carried back when written.
  EXPECT_GE(backward_carries, 3);
}

// No obstacle, the robot on a cell centre facing north, the goal east: a quarter turn on the spot
// (90 deg at 30 deg/s: 3 s), then one straight drive at 0.2 m/s.
TEST(GroundMissionTimelineTest, TurnsThenDrivesInAFreeField) {
  GroundMissionScene scene;
  scene.area_max_W = Eigen::Vector2d(6.0, 4.0);
  scene.robot_p_W = Eigen::Vector2d(1.025, 2.025);
  scene.robot_yaw_rad = kPi / 2;
  scene.goal_p_W = Eigen::Vector2d(5.025, 2.025);
  const GroundMissionParams params;
  const GroundMission mission = GroundMissionPlanner(scene, params).Plan();
  ASSERT_TRUE(mission.solved()) << mission;
  ASSERT_EQ(mission.legs.size(), 1u);
  ASSERT_EQ(mission.legs[0].waypoints.size(), 2u);
  const GroundMissionTimeline timeline(mission, scene, params);
  const double length_m = mission.path_length_m();
  EXPECT_NEAR(timeline.duration_s(), 3.0 + length_m / 0.2, 1e-9);
  EXPECT_LT(timeline.start_offset_W().norm(), 1e-12);

  const GroundRobotSample turning = timeline.Sample(1.5);
  EXPECT_EQ(turning.activity, "turn");
  EXPECT_EQ(turning.robot_p_W, scene.robot_p_W);
  EXPECT_NEAR(turning.robot_yaw_rad, kPi / 4, 1e-12);
  const GroundRobotSample driving = timeline.Sample(3.0 + 5.0);
  EXPECT_EQ(driving.activity, "drive");
  EXPECT_LT((driving.robot_p_W - (scene.robot_p_W + Eigen::Vector2d(1.0, 0.0))).norm(), 1e-9);
  EXPECT_NEAR(driving.robot_yaw_rad, 0.0, 1e-12);
  const GroundRobotSample done = timeline.Sample(timeline.duration_s());
  EXPECT_LT((done.robot_p_W - (scene.robot_p_W + Eigen::Vector2d(length_m, 0.0))).norm(), 1e-9);
}

// Fig. D.10's first cube: grasped in the corridor, carried back past its entrance, placed, and
// the robot drives forward to the grasp location again before the next leg.
TEST(GroundMissionTimelineTest, CarriesTheFirstCubeOfFigure10BackAndReturns) {
  const GroundMissionScene scene = testing::Figure10Scene();
  const GroundMissionParams params;
  const GroundMission mission = GroundMissionPlanner(scene, params).Plan();
  ASSERT_TRUE(mission.solved()) << mission;
  ASSERT_GT(mission.removals[0].backward_m, 0.0) << mission;
  const GroundMissionTimeline timeline(mission, scene, params);
  const GroundRemovalTimes& times = timeline.removal_times()[0];
  const GroundObstacleRemoval& removal = mission.removals[0];

  // Riding with the robot while it reverses: westwards (the corridor runs east), same heading.
  const GroundRobotSample early = timeline.Sample(times.grasp_end_s + 0.5);
  const GroundRobotSample later = timeline.Sample(times.grasp_end_s + 1.0);
  EXPECT_EQ(early.activity, "back");
  EXPECT_LT(later.robot_p_W.x(), early.robot_p_W.x());
  EXPECT_NEAR((later.robot_p_W - early.robot_p_W).norm(), 0.5 * params.driving_speed_mps, 1e-9);
  EXPECT_EQ(later.movable_p_W[0], later.robot_p_W);
  EXPECT_EQ(later.carried, 0);
  // Placed outside the corridor; then forward again, empty-handed, to where it grasped.
  const GroundRobotSample placed = timeline.Sample(times.place_end_s);
  EXPECT_EQ(placed.movable_p_W[0], removal.place_p_W);
  EXPECT_EQ(placed.carried, -1);
  EXPECT_EQ(placed.activity, "drive");
  const GroundRobotSample returned =
      timeline.Sample(times.place_end_s + removal.backward_m / params.driving_speed_mps);
  EXPECT_LT((returned.robot_p_W - removal.grasp_p_W - timeline.start_offset_W()).norm(), 1e-9);
  EXPECT_EQ(returned.leg, 1);
  // The mission time of the removal: grasp, back, place, forward.
  EXPECT_NEAR(times.place_end_s - times.grasp_start_s,
              params.remove_time_s + removal.backward_m / params.driving_speed_mps, 1e-9);
}

TEST(GroundMissionTimelineTest, RejectsWhatItCannotExecute) {
  const GroundMissionScene scene = testing::Figure10Scene();
  const GroundMissionParams params;
  EXPECT_THROW(GroundMissionTimeline(GroundMission{}, scene, params), std::invalid_argument);
  const GroundMission mission = GroundMissionPlanner(scene, params).Plan();
  ASSERT_TRUE(mission.solved()) << mission;
  GroundMissionScene fewer = scene;
  fewer.movable_obstacles.pop_back();
  EXPECT_THROW(GroundMissionTimeline(mission, fewer, params), std::invalid_argument);
  GroundMission moved = mission;
  moved.removals[2].place_s_m += 100.0;  // beyond the goal
  EXPECT_THROW(GroundMissionTimeline(moved, scene, params), std::invalid_argument);
  GroundMissionParams stopped = params;
  stopped.driving_speed_mps = 0.0;
  EXPECT_THROW(GroundMissionTimeline(mission, scene, stopped), std::invalid_argument);
  EXPECT_THROW(GroundMissionTimeline(mission, scene, params).Sample(std::nan("")),
               std::invalid_argument);
}

TEST(GroundMissionTimelineTest, DriveSegmentsAreTheOnlyTimesTheRobotMoves) {
  const GroundMissionScene scene = testing::Figure9aScene();
  GroundMissionParams params;
  params.driving_speed_mps = 0.3;
  const GroundMission mission = GroundMissionPlanner(scene, params).Plan();
  ASSERT_TRUE(mission.solved()) << mission;
  const GroundMissionTimeline timeline(mission, scene, params);
  const std::vector<GroundDriveSegment> segments = timeline.DriveSegments();
  ASSERT_FALSE(segments.empty());
  double driven_m = 0.0, previous_end_s = 0.0;
  for (const GroundDriveSegment& segment : segments) {
    ASSERT_GT(segment.end_s, segment.start_s);
    ASSERT_GE(segment.start_s, previous_end_s);
    // Straight at the driving speed: the chord is the distance driven.
    const Eigen::Vector2d a = timeline.Sample(segment.start_s).robot_p_W;
    const Eigen::Vector2d b = timeline.Sample(segment.end_s).robot_p_W;
    EXPECT_NEAR((b - a).norm(), (segment.end_s - segment.start_s) * params.driving_speed_mps, 1e-9);
    const Eigen::Vector2d middle = timeline.Sample((segment.start_s + segment.end_s) / 2).robot_p_W;
    EXPECT_LT((middle - (a + b) / 2).norm(), 1e-9);
    // Between two segments the robot stands (it turns, grasps or places).
    if (segment.start_s > previous_end_s) {
      const Eigen::Vector2d before = timeline.Sample(previous_end_s).robot_p_W;
      EXPECT_LT((timeline.Sample((previous_end_s + segment.start_s) / 2).robot_p_W - before).norm(),
                1e-9);
      EXPECT_LT((a - before).norm(), 1e-9);
    }
    driven_m += (b - a).norm();
    previous_end_s = segment.end_s;
  }
  double backward_m = 0.0;
  for (const GroundObstacleRemoval& removal : mission.removals) backward_m += removal.backward_m;
  EXPECT_NEAR(driven_m, mission.path_length_m() + 2 * backward_m, 1e-6);
}

TEST(GroundBoxTest, OverlapByTheSeparatingAxesAgreesWithPointsInside) {
  const GroundBox unit{Eigen::Vector2d::Zero(), Eigen::Vector2d(1.0, 1.0), 0.0};
  EXPECT_TRUE(BoxesOverlap(unit, {Eigen::Vector2d(0.9, 0.0), Eigen::Vector2d(1.0, 1.0), 0.0}));
  EXPECT_FALSE(BoxesOverlap(unit, {Eigen::Vector2d(1.1, 0.0), Eigen::Vector2d(1.0, 1.0), 0.0}));
  EXPECT_FALSE(BoxesOverlap(unit, {Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(1.0, 1.0), 0.0}));
  // A diamond beside the square's side: its corner at x = 1.1 - 0.707 reaches inside.
  EXPECT_TRUE(BoxesOverlap(unit, {Eigen::Vector2d(1.1, 0.0), Eigen::Vector2d(1.0, 1.0), kPi / 4}));
  // On the square's diagonal the diamond shows an edge: half-extents 0.707 (square) + 0.5.
  const Eigen::Vector2d diagonal = Eigen::Vector2d(1.0, 1.0).normalized();
  EXPECT_TRUE(BoxesOverlap(unit, {1.15 * diagonal, Eigen::Vector2d(1.0, 1.0), kPi / 4}));
  EXPECT_FALSE(BoxesOverlap(unit, {1.25 * diagonal, Eigen::Vector2d(1.0, 1.0), kPi / 4}));
  // Random pairs: a point of one inside the other means overlap, whatever the sizes and yaws.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> position(-1.0, 1.0), size(0.05, 1.0), yaw(-kPi, kPi);
  int overlapping = 0;
  for (int pair = 0; pair < 300; ++pair) {
    const GroundBox a{Eigen::Vector2d(position(rng), position(rng)),
                      Eigen::Vector2d(size(rng), size(rng)), yaw(rng)};
    const GroundBox b{Eigen::Vector2d(position(rng), position(rng)),
                      Eigen::Vector2d(size(rng), size(rng)), yaw(rng)};
    bool point_inside = false;
    for (const auto& [box, other] : {std::pair{a, b}, std::pair{b, a}}) {
      const Eigen::Rotation2Dd R(box.yaw_rad);
      for (int i = 1; i < 30; ++i) {
        for (int j = 1; j < 30; ++j) {
          const Eigen::Vector2d q = box.p_W + R * box.size_m.cwiseProduct(Eigen::Vector2d(
                                                      i / 30.0 - 0.5, j / 30.0 - 0.5));
          point_inside |= DistanceToBox(other, q) == 0.0;
        }
      }
    }
    overlapping += point_inside;
    if (point_inside) {
      EXPECT_TRUE(BoxesOverlap(a, b)) << pair;
    }
    // Far apart (centres beyond the sum of the circumscribed radii): never.
    if ((a.p_W - b.p_W).norm() > CircumscribedRadius(a) + CircumscribedRadius(b)) {
      EXPECT_FALSE(BoxesOverlap(a, b)) << pair;
    }
    EXPECT_EQ(BoxesOverlap(a, b), BoxesOverlap(b, a)) << pair;
  }
  EXPECT_GT(overlapping, 30);
}

}  // namespace
}  // namespace aperture::planning
