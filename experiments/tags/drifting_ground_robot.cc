#include "experiments/tags/drifting_ground_robot.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "control/constants.h"
#include "control/require.h"

namespace aperture::experiments {
namespace {

double WrappedRad(double angle_rad) { return std::remainder(angle_rad, 2.0 * control::kPi); }

}  // namespace

const char* ToString(GroundRobotState state) {
  switch (state) {
    case GroundRobotState::kWaitingToStart:
      return "waiting_to_start";
    case GroundRobotState::kExecuting:
      return "executing";
    case GroundRobotState::kWaitingForFix:
      return "waiting_for_fix";
    case GroundRobotState::kDone:
      return "done";
    case GroundRobotState::kFailSafe:
      return "fail_safe";
  }
  return "unknown";
}

DriftingGroundRobot::DriftingGroundRobot(const planning::GroundMissionTimeline& timeline,
                                         const GroundOdometryDriftParams& drift,
                                         const GroundRelocalizationParams& relocalization,
                                         std::uint64_t seed)
    : timeline_(timeline),

      drift_(drift),
      relocalization_(relocalization),
      rng_(seed),
      placed_offset_W_(timeline.removal_times().size()) {
  control::RequireNonNegative(drift.scale_sigma, "drift.scale_sigma");
  control::RequireNonNegative(drift.heading_sigma_rad, "drift.heading_sigma_rad");
  control::RequirePositive(relocalization.fix_timeout_s, "relocalization.fix_timeout_s");
  control::RequirePositive(relocalization.max_correction_m, "relocalization.max_correction_m");
  control::RequirePositive(relocalization.max_segment_m, "relocalization.max_segment_m");
  for (const planning::GroundDriveSegment& segment : timeline.DriveSegments()) {
    const double length_m =
        (timeline.Sample(segment.end_s).robot_p_W - timeline.Sample(segment.start_s).robot_p_W)
            .norm();
    const int pieces =
        relocalization.enabled
            ? std::max(1, static_cast<int>(std::ceil(length_m / relocalization.max_segment_m)))
            : 1;
    const double piece_s = (segment.end_s - segment.start_s) / pieces;
    for (int i = 0; i < pieces; ++i) {
      segments_.push_back({segment.start_s + i * piece_s,
                           i + 1 == pieces ? segment.end_s : segment.start_s + (i + 1) * piece_s});
    }
  }
}

void DriftingGroundRobot::Start(double t_s) {
  if (state_ != GroundRobotState::kWaitingToStart) return;
  state_ = GroundRobotState::kExecuting;
  t_s_ = t_s;
}

void DriftingGroundRobot::Advance(double t_s, const std::optional<GroundRobotFix>& fix) {
  if (state_ == GroundRobotState::kWaitingToStart || !(t_s > t_s_)) return;
  double now_s = t_s_;
  t_s_ = t_s;
  while (state_ == GroundRobotState::kExecuting || state_ == GroundRobotState::kWaitingForFix) {
    if (state_ == GroundRobotState::kWaitingForFix) {
      if (fix && fix->t_s > stop_t_s_) {
        TakeFix(*fix);
        continue;
      }
      if (t_s - stop_t_s_ > relocalization_.fix_timeout_s) {
        state_ = GroundRobotState::kFailSafe;
        fail_reason_ = "communication error: no fix of the robot for " +
                       std::to_string(relocalization_.fix_timeout_s) + " s after it stopped";
      }
      return;
    }
    // The next event of the execution: the end of the segment under way, the start of the next
    // one, or the end of the mission.
    const double event_s = command_                      ? segments_[segment_].end_s
                           : segment_ < segments_.size() ? segments_[segment_].start_s
                                                         : timeline_.duration_s();
    const double step_s = std::min(t_s - now_s, event_s - tau_s_);
    tau_s_ += step_s;
    now_s += step_s;
    for (size_t r = 0; r < placed_offset_W_.size(); ++r) {
      if (!placed_offset_W_[r] && tau_s_ >= timeline_.removal_times()[r].place_start_s) {
        placed_offset_W_[r] = TrueOffset();  // the robot stands still while it places
      }
    }
    if (tau_s_ < event_s) return;  // t_s reached
    if (command_) {
      EndSegment(now_s);
    } else if (segment_ < segments_.size()) {
      BeginSegment();
    } else {
      state_ = GroundRobotState::kDone;
    }
  }
}

void DriftingGroundRobot::BeginSegment() {
  const planning::GroundDriveSegment& segment = segments_[segment_];
  Command command;
  command.planned_W =
      timeline_.Sample(segment.end_s).robot_p_W - timeline_.Sample(segment.start_s).robot_p_W;
  // The turn before the segment was commanded from the believed heading.
  true_yaw_offset_rad_ = WrappedRad(true_yaw_offset_rad_ - belief_yaw_offset_rad_);
  belief_yaw_offset_rad_ = 0.0;
  const Eigen::Vector2d command_W = command.planned_W - belief_offset_W_;
  std::normal_distribution<double> normal(0.0, 1.0);
  const double scale = 1.0 + drift_.scale_sigma * normal(rng_);
  command.heading_drift_rad =
      drift_.heading_sigma_rad * std::sqrt(command.planned_W.norm()) * normal(rng_);
  command.true_W =
      scale *
      (Eigen::Rotation2Dd(true_yaw_offset_rad_ + command.heading_drift_rad / 2) * command_W);
  command_ = command;
}

void DriftingGroundRobot::EndSegment(double t_s) {
  true_offset_W_ += command_->true_W - command_->planned_W;
  true_yaw_offset_rad_ = WrappedRad(true_yaw_offset_rad_ + command_->heading_drift_rad);
  // Odometry integrated the command: the robot believes it stands at the planned end.
  belief_offset_W_.setZero();
  belief_yaw_offset_rad_ = 0.0;
  command_.reset();
  ++segment_;
  if (relocalization_.enabled) {
    state_ = GroundRobotState::kWaitingForFix;
    stop_t_s_ = t_s;
  }
}

void DriftingGroundRobot::TakeFix(const GroundRobotFix& fix) {
  const planning::GroundRobotSample planned = timeline_.Sample(tau_s_);
  const Eigen::Vector2d belief_W = planned.robot_p_W + belief_offset_W_;
  GroundRelocalization relocalization;
  relocalization.t_s = fix.t_s;
  relocalization.correction_m = (fix.p_W - belief_W).norm();
  relocalization.fix_error_m = (fix.p_W - (planned.robot_p_W + true_offset_W_)).norm();
  relocalizations_.push_back(relocalization);
  if (relocalization.correction_m > relocalization_.max_correction_m) {
    state_ = GroundRobotState::kFailSafe;
    fail_reason_ = "mapping error: the fix lies " + std::to_string(relocalization.correction_m) +
                   " m from the odometry (bound " +
                   std::to_string(relocalization_.max_correction_m) + " m)";
    return;
  }
  belief_offset_W_ = fix.p_W - planned.robot_p_W;
  belief_yaw_offset_rad_ = WrappedRad(fix.yaw_rad - planned.robot_yaw_rad);
  state_ = GroundRobotState::kExecuting;
}

Eigen::Vector2d DriftingGroundRobot::TrueOffset() const {
  if (!command_) return true_offset_W_;
  const planning::GroundDriveSegment& segment = segments_[segment_];
  const double f = (tau_s_ - segment.start_s) / (segment.end_s - segment.start_s);
  return true_offset_W_ + f * (command_->true_W - command_->planned_W);
}

double DriftingGroundRobot::TrueYawOffset() const {
  if (!command_) return true_yaw_offset_rad_;
  const planning::GroundDriveSegment& segment = segments_[segment_];
  const double f = (tau_s_ - segment.start_s) / (segment.end_s - segment.start_s);
  return true_yaw_offset_rad_ + f * command_->heading_drift_rad;
}

planning::GroundRobotSample DriftingGroundRobot::Now() const {
  planning::GroundRobotSample sample = timeline_.Sample(tau_s_);
  const Eigen::Vector2d offset_W = TrueOffset();
  const double yaw_offset_rad = TrueYawOffset();
  sample.robot_p_W += offset_W;
  sample.robot_yaw_rad = WrappedRad(sample.robot_yaw_rad + yaw_offset_rad);
  const std::vector<planning::GroundRemovalTimes>& times = timeline_.removal_times();
  for (size_t r = 0; r < times.size(); ++r) {
    const size_t k = static_cast<size_t>(times[r].obstacle);
    if (tau_s_ < times[r].grasp_start_s) continue;
    if (tau_s_ < times[r].grasp_end_s) {  // on its way from where it lies to the true gripper
      const double f =
          (tau_s_ - times[r].grasp_start_s) / (times[r].grasp_end_s - times[r].grasp_start_s);
      sample.movable_p_W[k] += f * offset_W;
      sample.movable_yaw_rad[k] = WrappedRad(sample.movable_yaw_rad[k] + f * yaw_offset_rad);
    } else if (tau_s_ < times[r].place_start_s) {  // riding with the robot
      sample.movable_p_W[k] += offset_W;
      sample.movable_yaw_rad[k] = WrappedRad(sample.movable_yaw_rad[k] + yaw_offset_rad);
    } else {
      sample.movable_p_W[k] += placed_offset_W_[r].value_or(offset_W);
    }
  }
  return sample;
}

}  // namespace aperture::experiments
