#pragma once
// The ground robot of paper D executing its planned mission in the simulator (issue 16 item 2;
// seed 001 Sec. D.6-D.7): straight segments driven open loop on wheel odometry that drifts,
// relocalized by the aerial robot between segments, and a fail-safe stop on mapping or
// communication errors (D.7.2: "the robots stopped to move and the error was reported").
//
// Model. planning::GroundMissionTimeline is the plan; each of its drive segments is driven as
// open-loop commands (with relocalization: pieces of at most max_segment_m, as the follower
// watches the robot anyway), each d_cmd from where the robot believes it stands to the piece's
// planned end. The wheels execute it with a distance scale error s and a heading error psi drawn
// per command (GroundOdometryDriftParams; psi's sigma grows with the square root of the length):
// the true displacement is (1 + s) R(e + psi / 2) d_cmd, e the heading error the robot carries
// into the command, which grows by psi over it. Odometry believes the command was executed
// exactly. Turns are commanded relative to the believed heading.
// - With relocalization the robot stops at the end of every segment until the aerial robot
//   reports its tag's pose (a GroundRobotFix) taken after it stopped; the fix replaces its
//   belief, so the next command corrects the position (and its turn the heading) error. A fix
//   farther than max_correction_m from the belief is taken for a mapping error, no fix within
//   fix_timeout_s for a communication error: either stops the robot for good (kFailSafe).
// - Without relocalization the errors accumulate over the segments.
// Grasping measures the obstacle with the robot's laser scanner (D.6): the obstacle comes to the
// robot's true gripper, rides with the robot and lies where the robot truly placed it.
// Times: the simulator's clock [s]; the timeline's execution time advances only while the robot
// moves (not while it waits for a fix).
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "planning/ground_mission/ground_mission_timeline.h"

namespace aperture::experiments {

struct GroundOdometryDriftParams {
  // Mecanum-wheel odometry (the youBot's) slips: a few percent of the distance driven.
  double scale_sigma = 0.03;        // distance error per segment, 1 sigma [fraction]
  double heading_sigma_rad = 0.02;  // heading change over 1 m of a command, 1 sigma [rad]
};

struct GroundRelocalizationParams {
  bool enabled = true;
  double fix_timeout_s = 3.0;     // no fix this long after stopping: communication error [s]
  double max_correction_m = 0.3;  // a fix farther from the belief: mapping error [m]
  double max_segment_m = 1.0;     // the longest drive between two fixes [m]
};

// The aerial robot's estimate of the ground robot's pose (its tag's) at sensor time t_s.
struct GroundRobotFix {
  double t_s = 0.0;
  Eigen::Vector2d p_W = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;
};

enum class GroundRobotState { kWaitingToStart, kExecuting, kWaitingForFix, kDone, kFailSafe };
const char* ToString(GroundRobotState state);

// One relocalization between segments.
struct GroundRelocalization {
  double t_s = 0.0;
  double correction_m = 0.0;  // |fix - belief|: the drift the fix removed
  double fix_error_m = 0.0;   // |fix - true position|
};

class DriftingGroundRobot {
 public:
  // `timeline` must outlive the robot. std::invalid_argument for negative sigmas or a
  // non-positive timeout or correction bound.
  DriftingGroundRobot(const planning::GroundMissionTimeline& timeline,
                      const GroundOdometryDriftParams& drift,
                      const GroundRelocalizationParams& relocalization, std::uint64_t seed);

  // The robot is commanded to go at t_s.
  void Start(double t_s);
  // Moves the robot on to t_s (calls at earlier or equal times change nothing); `fix` is the
  // aerial robot's latest fix, if any (used only while the robot waits for one).
  void Advance(double t_s, const std::optional<GroundRobotFix>& fix);

  // Where everything truly is now (robot, movable obstacles; activity and carried as planned).
  planning::GroundRobotSample Now() const;
  GroundRobotState state() const { return state_; }
  // Why the robot stopped in kFailSafe ("" otherwise).
  const std::string& fail_reason() const { return fail_reason_; }
  const std::vector<GroundRelocalization>& relocalizations() const { return relocalizations_; }
  // The open-loop commands, in timeline time (the drive segments, split when relocalizing).
  const std::vector<planning::GroundDriveSegment>& commands() const { return segments_; }
  // Seconds of the timeline executed so far.
  double execution_s() const { return tau_s_; }

 private:
  // The open-loop execution of drive segment `segment_` that is under way.
  struct Command {
    Eigen::Vector2d planned_W = Eigen::Vector2d::Zero();  // planned displacement
    Eigen::Vector2d true_W = Eigen::Vector2d::Zero();     // what the wheels do
    double heading_drift_rad = 0.0;                       // psi
  };
  void BeginSegment();
  void EndSegment(double t_s);
  void TakeFix(const GroundRobotFix& fix);
  Eigen::Vector2d TrueOffset() const;  // true - planned robot position now
  double TrueYawOffset() const;

  const planning::GroundMissionTimeline& timeline_;
  std::vector<planning::GroundDriveSegment> segments_;
  GroundOdometryDriftParams drift_;
  GroundRelocalizationParams relocalization_;
  std::mt19937_64 rng_;

  GroundRobotState state_ = GroundRobotState::kWaitingToStart;
  std::string fail_reason_;
  double t_s_ = 0.0;    // simulator time of the last Advance
  double tau_s_ = 0.0;  // timeline time
  size_t segment_ = 0;  // the next (or current) drive segment
  std::optional<Command> command_;
  double stop_t_s_ = 0.0;  // when the robot stopped to wait for a fix
  // Between segments: true - planned position and heading; belief - planned.
  Eigen::Vector2d true_offset_W_ = Eigen::Vector2d::Zero();
  double true_yaw_offset_rad_ = 0.0;
  Eigen::Vector2d belief_offset_W_ = Eigen::Vector2d::Zero();
  double belief_yaw_offset_rad_ = 0.0;
  std::vector<std::optional<Eigen::Vector2d>> placed_offset_W_;  // per removal
  std::vector<GroundRelocalization> relocalizations_;
};

}  // namespace aperture::experiments
