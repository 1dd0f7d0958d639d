#include "planning/tag_follow/tag_follow_autopilot.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "config/yaml_read_archive.h"
#include "control/constants.h"
#include "control/control_params_io.h"
#include "perception/estimation/pose_fusion_params_io.h"
#include "perception/tags/tag_detector_registry.h"
#include "perception/tags/tag_pose_estimator.h"
#include "planning/body_velocity_tracking.h"
#include "servo/level_view.h"
#include "servo/servo_params_io.h"

namespace aperture::planning {
namespace {

// The camera must look within this angle of straight down (-z_B) [deg].
constexpr double kMaxFollowCameraTiltDeg = 10.0;
// Peak over mean speed of a rest-to-rest minimum-jerk segment.
constexpr double kFollowMinimumJerkPeakToMean = 1.875;
// The largest turn about the optical axis left to the servo before the corners are matched to
// the goal view's next quarter turn (hysteresis above the 45 deg of the nearest one) [rad].
constexpr double kMaxQuarterTurnErrorRad = 60.0 * control::kDegToRad;

double HeadingOfRotation(const Eigen::Matrix3d& R_WB) { return std::atan2(R_WB(1, 0), R_WB(0, 0)); }

// R_C'C of servo/level_view.h: the tilted camera C seen from the level camera C'.
Eigen::Matrix3d LevelFromCamera(const Eigen::Matrix3d& R_WB, const Eigen::Matrix3d& R_BC) {
  const Eigen::Matrix3d R_WBlevel =
      Eigen::AngleAxisd(HeadingOfRotation(R_WB), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return R_BC.transpose() * R_WBlevel.transpose() * R_WB * R_BC;
}

}  // namespace

void TagFollowParams::Validate() const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("mission (follow): " + what);
  };
  require(target_id >= 0, "target_id must be >= 0");
  require(follow_height_m > 0.0 && std::isfinite(follow_height_m), "follow_height_m must be > 0");
  require(search_height_m > 0.0 && std::isfinite(search_height_m), "search_height_m must be > 0");
  require(max_speed_mps > 0.0 && std::isfinite(max_speed_mps), "max_speed_mps must be > 0");
  require(max_accel_mps2 > 0.0 && std::isfinite(max_accel_mps2), "max_accel_mps2 must be > 0");
  require(search_speed_mps > 0.0 && std::isfinite(search_speed_mps),
          "search_speed_mps must be > 0");
  require(settle_s >= 0.0 && std::isfinite(settle_s), "settle_s must be >= 0");
  require(lost_timeout_s > 0.0 && std::isfinite(lost_timeout_s), "lost_timeout_s must be > 0");
  require(lock_error > 0.0 && std::isfinite(lock_error), "lock_error must be > 0");
  require(lock_hold_s >= 0.0 && std::isfinite(lock_hold_s), "lock_hold_s must be >= 0");
  require(camera_id >= 0, "camera_id must be >= 0");
  servo.Validate();
  fusion.Validate();
}

void LoadParams(config::ParamReader& reader, TagFollowParams* params) {
  reader.Read("target_id", &params->target_id);
  reader.Read("follow_height_m", &params->follow_height_m);
  reader.Read("search_height_m", &params->search_height_m);
  reader.Read("max_speed_mps", &params->max_speed_mps);
  reader.Read("max_accel_mps2", &params->max_accel_mps2);
  reader.Read("search_speed_mps", &params->search_speed_mps);
  reader.Read("settle_s", &params->settle_s);
  reader.Read("lost_timeout_s", &params->lost_timeout_s);
  reader.Read("lock_error", &params->lock_error);
  reader.Read("lock_hold_s", &params->lock_hold_s);
  reader.Read("camera_id", &params->camera_id);
  reader.ReadSection("servo", &params->servo);
  reader.ReadSection("controller", &params->controller);
  reader.ReadSection("fusion", &params->fusion);
  reader.RejectUnknownKeys();
  reader.Validate(*params);
}

const char* ToString(TagFollowPhase phase) {
  switch (phase) {
    case TagFollowPhase::kSettle:
      return "settle";
    case TagFollowPhase::kSearch:
      return "search";
    case TagFollowPhase::kFollow:
      return "follow";
    case TagFollowPhase::kLost:
      return "lost";
  }
  return "unknown";
}

TagFollowAutopilot::TagFollowAutopilot(const TagFollowParams& params, double target_size_m,
                                       const Eigen::Vector2d& search_xy_W,
                                       std::shared_ptr<const perception::CameraModel> camera,
                                       const Eigen::Isometry3d& T_BC,
                                       const control::VehicleParameters& vehicle,
                                       const perception::TagFrontEndParams& front_end)
    : params_((params.Validate(), params)),
      target_size_m_(target_size_m),
      search_xy_W_(search_xy_W),
      camera_(camera ? std::move(camera)
                     : throw std::invalid_argument(
                           "TagFollowAutopilot: camera is null; pass the downward camera")),
      T_BC_(T_BC),
      vehicle_(vehicle),
      front_end_(perception::TagDetectorRegistry::WithBuiltins().Create(front_end.detector,
                                                                        front_end.detection),
                 camera_, front_end),
      servo_(params.servo, T_BC),
      controller_(vehicle, params.controller),
      fusion_(params.fusion) {
  perception::RequireRigid(T_BC_, "TagFollowAutopilot T_BC");
  if (T_BC_.linear().col(2).dot(-Eigen::Vector3d::UnitZ()) <
      std::cos(kMaxFollowCameraTiltDeg * M_PI / 180.0)) {
    throw std::invalid_argument(
        "TagFollowAutopilot: the camera does not look down (its z_C is more than 10 deg off "
        "-z_B); mount it looking down");
  }
  if (!(target_size_m_ > 0.0) || !std::isfinite(target_size_m_)) {
    throw std::invalid_argument("TagFollowAutopilot: target_size_m must be > 0");
  }
  if (!search_xy_W_.allFinite()) {
    throw std::invalid_argument("TagFollowAutopilot: search_xy_W must be finite");
  }
  // The goal view: the tag centred below the level camera, x_T along x_C, at follow_height_m
  // (matched to the seen corners up to a quarter turn: ServoOn).
  for (int k = 0; k < 4; ++k) {
    desired_[k] = perception::TagCorner(k, target_size_m_).head<2>() / params_.follow_height_m;
  }
  servo_.SetDesired(desired_, params_.follow_height_m);
}

void TagFollowAutopilot::OnImu(const perception::ImuSample& sample) { fusion_.AddImu(sample); }

void TagFollowAutopilot::OnOdometry(const perception::PoseMeasurement& pose_WB) {
  fusion_.AddPose(pose_WB);
}

std::optional<control::QuadState> TagFollowAutopilot::Estimate() const {
  const std::optional<perception::PoseImuEstimate> e = fusion_.estimate();
  if (!e) return std::nullopt;
  return e->state;
}

void TagFollowAutopilot::OnFrame(const perception::Frame& frame) {
  if (frame.camera_id != params_.camera_id) return;
  cv::Mat gray = frame.image;
  if (gray.channels() == 3) cv::cvtColor(frame.image, gray, cv::COLOR_BGR2GRAY);
  const perception::TagFrameResult result = front_end_.Process(gray, frame.t_s);
  TagFollowSample sample;
  sample.t_s = frame.t_s;
  last_corners_px_.reset();
  const std::optional<control::QuadState> x = Estimate();
  for (const perception::TagResult& tag : result.tags) {
    if (tag.detection.id != params_.target_id || !tag.pose) continue;
    sample.target_seen = true;
    last_corners_px_ = tag.detection.corners_px;
    for (const Eigen::Vector2d& corner : tag.detection.corners_px) {
      sample.target_center_px += corner / 4.0;
    }
    if (x) {
      Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
      T_WB.linear() = x->q_WB.toRotationMatrix();
      T_WB.translation() = x->p_WB;
      sample.T_WT = T_WB * T_BC_ * tag.chosen().T_CT;
      ServoOn(tag, frame.t_s, *x);
      sample.servo_error = servo_error_;
      sample.v_B = reference_.v_B;
      sample.yaw_rate_radps = reference_.yaw_rate_radps;
    }
    break;
  }
  trace_.push_back(sample);
}

void TagFollowAutopilot::ServoOn(const perception::TagResult& tag, double t_s,
                                 const control::QuadState& x) {
  const Eigen::Matrix3d R_WB = x.q_WB.toRotationMatrix();
  std::vector<Eigen::Vector2d> corners_n;
  for (const Eigen::Vector2d& corner_px : tag.detection.corners_px) {
    const Eigen::Vector3d bearing = camera_->Unproject(corner_px);
    if (!(bearing.z() > 0.0)) return;
    corners_n.push_back(bearing.hnormalized());
  }
  const std::optional<std::vector<Eigen::Vector2d>> level =
      servo::LevelView(corners_n, R_WB, T_BC_.linear());
  if (!level) return;
  const double depth_m =
      (LevelFromCamera(R_WB, T_BC_.linear()) * tag.chosen().T_CT.translation()).z();
  if (!(depth_m > 0.0)) return;
  // Point-feature IBVS drives the camera away from a target turned by ~pi about the optical axis
  // (Chaumette's "camera retreat"; a robot facing against the goal view did climb out of sight):
  // the corners are matched to the goal view turned by the quarter turn nearest to the tag's,
  // kept while within kMaxQuarterTurnErrorRad, so the servo itself turns at most that far.
  const auto edge_angle_rad = [&](int shift) {
    const Eigen::Vector2d edge = (*level)[(shift + 1) % 4] - (*level)[shift % 4];
    const Eigen::Vector2d goal = desired_[1] - desired_[0];
    return std::abs(std::atan2(goal.x() * edge.y() - goal.y() * edge.x(), goal.dot(edge)));
  };
  if (edge_angle_rad(corner_shift_) > kMaxQuarterTurnErrorRad) {
    for (int shift = 0; shift < 4; ++shift) {
      if (edge_angle_rad(shift) < edge_angle_rad(corner_shift_)) corner_shift_ = shift;
    }
  }
  servo::PointServo::Corners corners;
  for (int k = 0; k < 4; ++k) corners[k] = (*level)[(k + corner_shift_) % 4];
  // What the vehicle did: its estimated velocity in the level body frame and heading rate.
  const double heading_rad = HeadingOfRotation(R_WB);
  servo::BodyVelocityReference own_motion;
  own_motion.v_B = Eigen::AngleAxisd(-heading_rad, Eigen::Vector3d::UnitZ()) * x.v_W;
  own_motion.yaw_rate_radps = (R_WB * x.omega_B).z();
  const servo::ServoStepResult step = servo_.Step(t_s, corners, depth_m, own_motion);
  if (step.status != servo::ServoStatus::kOk) return;
  reference_ = step.reference;
  const double speed = reference_.v_B.norm();
  if (speed > params_.max_speed_mps) reference_.v_B *= params_.max_speed_mps / speed;
  servo_error_ = step.error_norm;
  if (!first_seen_t_s_) first_seen_t_s_ = t_s;
  if (servo_error_ >= params_.lock_error) {
    below_lock_since_t_s_.reset();
  } else if (!below_lock_since_t_s_) {
    below_lock_since_t_s_ = t_s;
  }
  if (!locked_t_s_ && below_lock_since_t_s_ &&
      t_s - *below_lock_since_t_s_ >= params_.lock_hold_s) {
    locked_t_s_ = t_s;
  }
  last_seen_t_s_ = t_s;
}

perception::AutopilotCommand TagFollowAutopilot::Command(
    const control::QuadState& x, const control::TrajectoryPoint& reference) const {
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = controller_.Compute(x, reference).command;
  return command;
}

perception::AutopilotCommand TagFollowAutopilot::Step(double t_s) {
  const std::optional<control::QuadState> x = Estimate();
  if (!x) {  // no odometry yet: level, hover thrust (the SITL starts hovering)
    perception::AutopilotCommand command;
    command.kind = perception::AutopilotCommand::Kind::kThrustRates;
    command.thrust_rates.collective_thrust_mps2 = vehicle_.gravity_mps2;
    return command;
  }
  const double dt_s = started_ ? t_s - last_step_t_s_ : 0.0;
  last_step_t_s_ = t_s;
  if (!started_) {
    started_ = true;
    phase_start_t_s_ = t_s;
    hold_p_W_ = x->p_WB;
    heading_rad_ = HeadingOfRotation(x->q_WB.toRotationMatrix());
  }
  const bool seen = t_s - last_seen_t_s_ <= params_.lost_timeout_s;
  if (seen && phase_ != TagFollowPhase::kFollow) {
    phase_ = TagFollowPhase::kFollow;
    phase_start_t_s_ = t_s;
    v_ref_W_ = x->v_W;  // the rate limit starts from the motion the vehicle has
  } else if (!seen && phase_ == TagFollowPhase::kFollow) {
    phase_ = TagFollowPhase::kLost;
    phase_start_t_s_ = t_s;
    hold_p_W_ = x->p_WB;
  }
  if (phase_ == TagFollowPhase::kSettle && t_s - phase_start_t_s_ >= params_.settle_s) {
    phase_ = TagFollowPhase::kSearch;
    phase_start_t_s_ = t_s;
    // The body below the camera at search height above search_xy_W (the ground at z_W = 0).
    const Eigen::Matrix3d R_WB_level =
        Eigen::AngleAxisd(heading_rad_, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d p_WC_goal(search_xy_W_.x(), search_xy_W_.y(), params_.search_height_m);
    const Eigen::Vector3d p_WB_goal = p_WC_goal - R_WB_level * T_BC_.translation();
    const double duration_s =
        std::max(1.0, kFollowMinimumJerkPeakToMean * (p_WB_goal - x->p_WB).norm() /
                          params_.search_speed_mps);
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    search_ = MotionPrimitive(hold_p_W_, zero, zero, p_WB_goal, zero, zero, duration_s);
  }
  control::TrajectoryPoint reference;
  reference.t_s = t_s;
  reference.p_W = hold_p_W_;
  reference.heading_rad = heading_rad_;
  if (phase_ == TagFollowPhase::kSearch) {
    reference = search_->Sample(std::min(t_s - phase_start_t_s_, search_->duration_s()));
    reference.t_s = t_s;
    reference.heading_rad = heading_rad_;
  } else if (phase_ == TagFollowPhase::kFollow) {
    heading_rad_ += reference_.yaw_rate_radps * dt_s;
    const Eigen::AngleAxisd R_W_level(heading_rad_, Eigen::Vector3d::UnitZ());
    const Eigen::Vector3d change_W = R_W_level * reference_.v_B - v_ref_W_;
    const double max_change = params_.max_accel_mps2 * dt_s;
    v_ref_W_ += change_W.norm() > max_change ? change_W * (max_change / change_W.norm()) : change_W;
    reference = BodyVelocityTrajectoryPoint(
        t_s, x->p_WB, heading_rad_, R_W_level.inverse() * v_ref_W_, reference_.yaw_rate_radps);
  }
  return Command(*x, reference);
}

std::string TagFollowAutopilot::status() const {
  std::string line = std::string("tag follow: ") + ToString(phase_);
  if (phase_ == TagFollowPhase::kFollow) {
    char buffer[96];
    std::snprintf(buffer, sizeof(buffer), ", |s - s*| %.3f, |v| %.2f m/s", servo_error_,
                  reference_.v_B.norm());
    line += buffer;
  }
  return line;
}

void TagFollowAutopilot::DrawOverlay(cv::Mat& bgr) const {
  const cv::Point center(bgr.cols / 2, bgr.rows / 2);
  cv::drawMarker(bgr, center, cv::Scalar(255, 255, 255), cv::MARKER_CROSS, 16, 1);
  // The acceptance band of issue 16: 10 % of the image width around the centre.
  cv::circle(bgr, center, static_cast<int>(0.1 * bgr.cols), cv::Scalar(200, 200, 200), 1,
             cv::LINE_AA);
  if (!last_corners_px_) return;
  std::vector<cv::Point> polygon;
  for (const Eigen::Vector2d& corner : *last_corners_px_) {
    polygon.emplace_back(cvRound(corner.x()), cvRound(corner.y()));
  }
  const cv::Scalar color =
      phase_ == TagFollowPhase::kFollow ? cv::Scalar(0, 220, 0) : cv::Scalar(0, 200, 255);
  cv::polylines(bgr, polygon, true, color, 2, cv::LINE_AA);
}

}  // namespace aperture::planning
