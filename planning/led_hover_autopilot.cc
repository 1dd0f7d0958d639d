#include "planning/led_hover_autopilot.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace aperture::planning {
namespace {

// Rotations from calibration files carry ~1e-9 rounding; 1e-6 flags real mistakes (a scaled or
// sheared matrix, a reflection) without rejecting round-off.
constexpr double kRotationTolerance = 1e-6;

void RequireRigid(const Eigen::Isometry3d& T, const std::string& name) {
  const Eigen::Matrix3d R = T.linear();
  if (!R.allFinite() || !T.translation().allFinite()) {
    throw std::invalid_argument(name + " must be finite");
  }
  const double orthonormality = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  if (orthonormality > kRotationTolerance || R.determinant() < 0.0) {
    throw std::invalid_argument(name + " is not a rigid transform (rotation part not orthonormal "
                                "with determinant +1, |R^T R - I| = " +
                                std::to_string(orthonormality) + "): give a proper rotation");
  }
}

}  // namespace

Eigen::Isometry3d BodyPoseFromLedPose(const Eigen::Isometry3d& T_WC, const Eigen::Isometry3d& T_CT,
                                      const Eigen::Isometry3d& T_BT) {
  RequireRigid(T_WC, "T_WC");
  RequireRigid(T_CT, "T_CT");
  RequireRigid(T_BT, "T_BT");
  return T_WC * T_CT * T_BT.inverse(Eigen::Isometry);
}

perception::PoseMeasurement LedTargetPoseMeasurement(double t_s, const Eigen::Isometry3d& T_WC,
                                                     const Eigen::Isometry3d& T_CT,
                                                     const perception::Matrix6d& covariance_CT,
                                                     const Eigen::Isometry3d& T_BT) {
  RequireRigid(T_WC, "T_WC");
  RequireRigid(T_CT, "T_CT");
  RequireRigid(T_BT, "T_BT");
  if (!std::isfinite(t_s)) throw std::invalid_argument("LED pose time t_s must be finite");
  if (!covariance_CT.allFinite()) {
    throw std::invalid_argument("LED pose covariance (T_CT) must be finite");
  }
  const Eigen::Isometry3d T_WT = T_WC * T_CT;
  perception::PoseMeasurement z;
  z.t_s = t_s;
  z.p_WX = T_WT.translation();
  z.q_WX = Eigen::Quaterniond(T_WT.linear()).normalized();
  z.p_BX = T_BT.translation();
  z.q_BX = Eigen::Quaterniond(T_BT.linear()).normalized();
  perception::Matrix6d J = perception::Matrix6d::Zero();
  J.topLeftCorner<3, 3>() = T_WC.linear();
  J.bottomRightCorner<3, 3>() = T_CT.linear().transpose();  // R_TC
  z.covariance = J * covariance_CT * J.transpose();
  z.covariance = 0.5 * (z.covariance + z.covariance.transpose()).eval();
  return z;
}

void LedHoverAutopilotParams::Validate() const {
  if (camera_id < 0) {
    throw std::invalid_argument("LedHoverAutopilotParams.camera_id must be >= 0, got " +
                                std::to_string(camera_id));
  }
  RequireRigid(T_WC, "LedHoverAutopilotParams.T_WC");
  RequireRigid(T_BT, "LedHoverAutopilotParams.T_BT");
  hold.Validate();
}

LedHoverAutopilot::LedHoverAutopilot(const control::VehicleParameters& vehicle,
                                     perception::LedConfiguration configuration,
                                     std::shared_ptr<const perception::CameraModel> camera,
                                     const LedHoverAutopilotParams& params)
    : params_(params),
      tracker_(std::move(configuration),
               camera ? std::move(camera)
                      : throw std::invalid_argument(
                            "LedHoverAutopilot: the LED camera model is null: pass the model of "
                            "the camera that observes the LEDs"),
               params.tracker),
      hold_(vehicle, params.hold, params.setpoint) {
  params_.Validate();
}

void LedHoverAutopilot::OnImu(const perception::ImuSample& sample) { hold_.AddImu(sample); }

void LedHoverAutopilot::OnFrame(const perception::Frame& frame) {
  if (frame.camera_id != params_.camera_id) return;
  const perception::LedTrackResult track = tracker_.Track(frame.image, frame.t_s);
  LedHoverFrameRecord record;
  record.t_s = frame.t_s;
  record.track_status = track.status;
  ++counts_.frames;
  if (track.has_pose()) {
    ++counts_.frames_with_pose;
    record.has_pose = true;
    record.T_WB = BodyPoseFromLedPose(params_.T_WC, *track.T_CT, params_.T_BT);
    record.update = hold_.AddPose(LedTargetPoseMeasurement(frame.t_s, params_.T_WC, *track.T_CT,
                                                           *track.covariance, params_.T_BT));
    if (record.update.initialized_filter) ++counts_.filter_starts;
    if (!record.update.initialized_filter && record.update.update.applied()) ++counts_.poses_applied;
    if (record.update.update.status == perception::PoseUpdateStatus::kRejectedOutlier) {
      ++counts_.poses_rejected;
    }
  }
  last_frame_ = record;
}

perception::AutopilotCommand LedHoverAutopilot::Step(double t_s) {
  last_step_t_s_ = t_s;
  return hold_.Step(t_s);
}

std::string LedHoverAutopilot::status() const { return hold_.status(last_step_t_s_); }

}  // namespace aperture::planning
