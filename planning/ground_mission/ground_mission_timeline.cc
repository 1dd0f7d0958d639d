#include "planning/ground_mission/ground_mission_timeline.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/constants.h"
#include "control/require.h"

namespace aperture::planning {
namespace {

using control::kDegToRad;
using control::kPi;

// Arc lengths of the mission and of the path rebuilt from its legs agree to rounding.
constexpr double kArcTolerance_m = 1e-9;

// The yaw after the fraction f of the shortest turn from from_rad to to_rad, in [-pi, pi].
double TurnedYaw(double from_rad, double to_rad, double f) {
  const double turn_rad = std::remainder(to_rad - from_rad, 2.0 * kPi);
  return std::remainder(from_rad + f * turn_rad, 2.0 * kPi);
}

void ValidateMission(const GroundMission& mission, const GroundMissionScene& scene) {
  if (!mission.solved()) {
    throw std::invalid_argument(
        "GroundMissionTimeline: the mission is not solved (no order reaches the goal); only a "
        "solved mission can be executed");
  }
  if (mission.legs.size() != mission.removals.size() + 1) {
    throw std::invalid_argument("GroundMissionTimeline: the mission has " +
                                std::to_string(mission.legs.size()) + " legs for " +
                                std::to_string(mission.removals.size()) +
                                " removals; it needs one leg per removal and one to the goal");
  }
  for (size_t i = 0; i < mission.legs.size(); ++i) {
    if (mission.legs[i].waypoints.empty()) {
      throw std::invalid_argument("GroundMissionTimeline: leg " + std::to_string(i) +
                                  " has no waypoint");
    }
  }
  for (size_t i = 0; i < mission.removals.size(); ++i) {
    const int obstacle = mission.removals[i].obstacle;
    if (obstacle < 0 || obstacle >= static_cast<int>(scene.movable_obstacles.size()) ||
        mission.legs[i].target != obstacle) {
      throw std::invalid_argument(
          "GroundMissionTimeline: removal " + std::to_string(i) + " names obstacle " +
          std::to_string(obstacle) +
          ", not a movable obstacle of the scene or not the target of its leg; plan the mission "
          "on this scene");
    }
  }
}

}  // namespace

GroundMissionTimeline::GroundMissionTimeline(const GroundMission& mission,
                                             const GroundMissionScene& scene,
                                             const GroundMissionParams& params)
    : scene_(scene), removals_(mission.removals) {
  ValidateMission(mission, scene);
  control::RequirePositive(params.driving_speed_mps, "GroundMissionParams.driving_speed_mps");
  control::RequirePositive(params.turn_rate_deg_s, "GroundMissionParams.turn_rate_deg_s");
  control::RequireNonNegative(params.remove_time_s, "GroundMissionParams.remove_time_s");
  path_ = BuildMissionPath(mission.legs).polyline;
  start_offset_W_ = scene.robot_p_W - mission.legs.front().waypoints.front().p_W;
  const double turn_rate_rad_s = params.turn_rate_deg_s * kDegToRad;
  const double handle_s = params.remove_time_s / 2;  // grasping, and placing

  // The robot's state while the phases are laid out.
  double t_s = 0.0;
  double s_m = 0.0;
  double yaw_rad = scene.robot_yaw_rad;
  int leg = 0;
  int pending = -1;  // the removal whose obstacle is carried to a place ahead
  const auto add = [&](const char* activity, double duration_s, double to_s_m, double to_yaw_rad) {
    if (duration_s > 0.0) {
      phases_.push_back({activity, leg, t_s, duration_s, s_m, to_s_m, yaw_rad, to_yaw_rad});
    }
    t_s += duration_s;
    s_m = to_s_m;
  };
  const auto drive = [&](const char* activity, double to_s_m) {
    add(activity, std::abs(to_s_m - s_m) / params.driving_speed_mps, to_s_m, yaw_rad);
  };
  const auto place = [&](size_t removal) {
    removal_times_[removal].place_start_s = t_s;
    add("place", handle_s, s_m, yaw_rad);
    removal_times_[removal].place_end_s = t_s;
  };
  // Places the obstacle carried ahead if the robot has reached its place (to rounding); at the
  // end of a leg it must have. At a waypoint the robot first turns to the next piece: the place
  // search put the place beside that piece (PlaceSearchContext, DirectionAt).
  const auto place_pending = [&](bool leg_end) {
    if (pending < 0) return;
    const GroundObstacleRemoval& removal = removals_[static_cast<size_t>(pending)];
    if (removal.place_s_m <= s_m + kArcTolerance_m) {
      place(static_cast<size_t>(pending));
      pending = -1;
    } else if (leg_end) {
      throw std::invalid_argument("GroundMissionTimeline: obstacle " +
                                  std::to_string(removal.obstacle) + " is placed at arc length " +
                                  std::to_string(removal.place_s_m) +
                                  " m, beyond the next grasp location at " + std::to_string(s_m) +
                                  " m; plan the mission on this scene");
    }
  };
  const auto drive_forward = [&](double to_s_m) {
    if (pending >= 0) {
      const double place_s_m = removals_[static_cast<size_t>(pending)].place_s_m;
      if (place_s_m < to_s_m) {  // within the piece (at its end: after the turn there)
        drive("drive", std::max(s_m, place_s_m));
        place_pending(false);
      }
    }
    drive("drive", to_s_m);
  };

  removal_times_.resize(removals_.size());
  for (size_t i = 0; i < mission.legs.size(); ++i) {
    leg = static_cast<int>(i);
    // GroundMissionPlanner::MakeLeg's count: turn to each waypoint's yaw, drive to the next.
    const std::vector<GroundWaypoint>& waypoints = mission.legs[i].waypoints;
    double waypoint_s_m = s_m;
    for (size_t j = 0; j < waypoints.size(); ++j) {
      if (j > 0) {
        waypoint_s_m += (waypoints[j].p_W - waypoints[j - 1].p_W).norm();
        drive_forward(waypoint_s_m);
      }
      const double turn_rad = std::remainder(waypoints[j].yaw_rad - yaw_rad, 2.0 * kPi);
      add("turn", std::abs(turn_rad) / turn_rate_rad_s, s_m, waypoints[j].yaw_rad);
      yaw_rad = waypoints[j].yaw_rad;
      place_pending(j + 1 == waypoints.size());
    }
    if (i == removals_.size()) break;  // the goal leg
    const GroundObstacleRemoval& removal = removals_[i];
    if (std::abs(removal.grasp_s_m - s_m) > kArcTolerance_m) {
      throw std::invalid_argument("GroundMissionTimeline: removal " + std::to_string(i) +
                                  " grasps at arc length " + std::to_string(removal.grasp_s_m) +
                                  " m, its leg ends at " + std::to_string(s_m) +
                                  " m; plan the mission on this scene");
    }
    GroundRemovalTimes& times = removal_times_[i];
    times.obstacle = removal.obstacle;
    times.grasp_start_s = t_s;
    add("grasp", handle_s, s_m, yaw_rad);
    times.grasp_end_s = t_s;
    if (removal.backward_m > 0.0) {  // carried back, then forward to the grasp location again
      const double grasp_s_m = s_m;
      drive("back", removal.place_s_m);
      place(i);
      drive("drive", grasp_s_m);
    } else {
      pending = static_cast<int>(i);
      place_pending(false);
    }
  }
  duration_s_ = t_s;
  final_yaw_rad_ = yaw_rad;
  last_leg_ = static_cast<int>(mission.legs.size()) - 1;
}

GroundRobotSample GroundMissionTimeline::Sample(double t_s) const {
  if (std::isnan(t_s)) {
    throw std::invalid_argument("GroundMissionTimeline::Sample: t_s is NaN; pass a time in s");
  }
  const double t = std::clamp(t_s, 0.0, duration_s_);
  GroundRobotSample sample;
  if (t >= duration_s_) {
    sample.robot_p_W = path_.PointAt(path_.length_m()) + start_offset_W_;
    sample.robot_yaw_rad = std::remainder(final_yaw_rad_, 2.0 * kPi);
    sample.activity = "done";
    sample.leg = last_leg_;
  } else {
    const auto after =
        std::upper_bound(phases_.begin(), phases_.end(), t,
                         [](double time_s, const Phase& phase) { return time_s < phase.start_s; });
    const Phase& phase = *(after - 1);
    const double fraction = (t - phase.start_s) / phase.duration_s;
    sample.robot_p_W = path_.PointAt(phase.from_s_m + fraction * (phase.to_s_m - phase.from_s_m)) +
                       start_offset_W_;
    sample.robot_yaw_rad = TurnedYaw(phase.from_yaw_rad, phase.to_yaw_rad, fraction);
    sample.activity = phase.activity;
    sample.leg = phase.leg;
  }

  for (const GroundBox& box : scene_.movable_obstacles) {
    sample.movable_p_W.push_back(box.p_W);
    sample.movable_yaw_rad.push_back(box.yaw_rad);
  }
  for (size_t r = 0; r < removal_times_.size(); ++r) {
    const GroundRemovalTimes& times = removal_times_[r];
    if (t < times.grasp_start_s) continue;
    const size_t k = static_cast<size_t>(times.obstacle);
    Eigen::Vector2d& p_W = sample.movable_p_W[k];
    double& yaw_rad = sample.movable_yaw_rad[k];
    const Eigen::Vector2d own_p_W = p_W;
    const double own_yaw_rad = yaw_rad;
    if (t < times.place_end_s) sample.carried = times.obstacle;
    if (t < times.grasp_end_s) {  // from its place onto the robot
      const double f = (t - times.grasp_start_s) / (times.grasp_end_s - times.grasp_start_s);
      p_W = own_p_W + f * (sample.robot_p_W - own_p_W);
      yaw_rad = TurnedYaw(own_yaw_rad, sample.robot_yaw_rad, f);
    } else if (t < times.place_start_s) {  // riding with the robot
      p_W = sample.robot_p_W;
      yaw_rad = sample.robot_yaw_rad;
    } else if (t < times.place_end_s) {  // from the robot to its new place
      const double f = (t - times.place_start_s) / (times.place_end_s - times.place_start_s);
      p_W = sample.robot_p_W + f * (removals_[r].place_p_W - sample.robot_p_W);
      yaw_rad = TurnedYaw(sample.robot_yaw_rad, own_yaw_rad, f);
    } else {
      p_W = removals_[r].place_p_W;
    }
  }
  return sample;
}

std::vector<GroundDriveSegment> GroundMissionTimeline::DriveSegments() const {
  std::vector<GroundDriveSegment> segments;
  for (const Phase& phase : phases_) {
    if (phase.from_s_m != phase.to_s_m) {
      segments.push_back({phase.start_s, phase.start_s + phase.duration_s});
    }
  }
  return segments;
}

}  // namespace aperture::planning
