#pragma once
// LED-stabilized hover (Faessler thesis, Appendix C.4.3): a camera fixed in the world (e.g. on
// a ground robot, pose T_WC) observes the infrared LEDs on the vehicle (target frame T, mounted at
// T_BT in the body); every frame goes through perception::LedTracker, whose T_CT with its
// covariance (C.9) becomes a pose measurement of T in W for PoseHold (pose + IMU filter and
// position controller at the set-point). Only the LED pose and the IMU are used: this runs on
// hardware (frames from the ground camera's link, IMU from the flight controller) as in SITL.
//
// Frames (STYLE.md 1): T_WT = T_WC * T_CT, T_WB = T_WT * T_TB = T_WC * T_CT * T_BT^-1.
// Covariance: LedTracker's [p_CT (C) m; rotation (C, left perturbation) rad] maps to the
// filter's [p_WT (W); rotation (T, right perturbation)] by blkdiag(R_WC, R_TC)
// (R_WC Exp(d_C) R_CT = R_WT Exp(R_TC d_C)).
#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "perception/autopilot.h"
#include "perception/camera/camera_model.h"
#include "perception/estimation/pose_imu_filter.h"
#include "perception/led/led_configuration.h"
#include "perception/led/led_tracker.h"
#include "planning/pose_hold.h"

namespace aperture::planning {

// p_W of the body from the LED target pose: T_WB = T_WC * T_CT * T_BT^-1. Throws
// std::invalid_argument naming the transform when one is not finite or its rotation is not
// orthonormal with determinant +1 (tolerance 1e-6).
Eigen::Isometry3d BodyPoseFromLedPose(const Eigen::Isometry3d& T_WC, const Eigen::Isometry3d& T_CT,
                                      const Eigen::Isometry3d& T_BT);

// The PoseImuFilter measurement of frame X = T at t_s (pose T_WC * T_CT, extrinsics T_BT) with
// the covariance mapped as in the header comment. Throws like BodyPoseFromLedPose, and for a
// non-finite covariance.
perception::PoseMeasurement LedTargetPoseMeasurement(double t_s, const Eigen::Isometry3d& T_WC,
                                                     const Eigen::Isometry3d& T_CT,
                                                     const perception::Matrix6d& covariance_CT,
                                                     const Eigen::Isometry3d& T_BT);

struct LedHoverAutopilotParams {
  int camera_id = 0;                                       // Frame::camera_id of the LED camera
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();  // LED camera in W (calibrated)
  Eigen::Isometry3d T_BT = Eigen::Isometry3d::Identity();  // LED target frame in B
  PoseHoldSetpoint setpoint;
  perception::LedTrackerParams tracker;
  PoseHoldParams hold;
  // Throws std::invalid_argument naming the field: negative camera_id, non-rigid or non-finite
  // T_WC / T_BT, invalid hold params or set-point.
  void Validate() const;
};

// One frame of the LED camera, as processed.
struct LedHoverFrameRecord {
  double t_s = 0.0;  // frame stamp (mid-exposure) [s]
  perception::LedTrackStatus track_status = perception::LedTrackStatus::kNoDetections;
  bool has_pose = false;
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();  // measured body pose (has_pose)
  PoseHoldUpdate update;                                   // (has_pose)
};

struct LedHoverCounts {
  int frames = 0;             // LED-camera frames processed
  int frames_with_pose = 0;   // LedTracker returned T_CT
  int poses_applied = 0;      // fused by the filter
  int poses_rejected = 0;     // gated as outliers
  int filter_starts = 0;      // first start + restarts after consecutive outliers
};

class LedHoverAutopilot : public perception::Autopilot {
 public:
  // `camera`: model of the LED camera (required); throws std::invalid_argument for it being null
  // or invalid parameters.
  LedHoverAutopilot(const control::VehicleParameters& vehicle,
                    perception::LedConfiguration configuration,
                    std::shared_ptr<const perception::CameraModel> camera,
                    const LedHoverAutopilotParams& params);

  std::string name() const override { return "led_hover"; }
  void OnImu(const perception::ImuSample& sample) override;
  // Frames of other cameras are ignored.
  void OnFrame(const perception::Frame& frame) override;
  perception::AutopilotCommand Step(double t_s) override;
  std::string status() const override;

  const PoseHold& hold() const { return hold_; }
  // The latest LED-camera frame (for logs: a driver reads it after each OnFrame).
  const LedHoverFrameRecord& last_frame() const { return last_frame_; }
  const LedHoverCounts& counts() const { return counts_; }

 private:
  LedHoverAutopilotParams params_;
  perception::LedTracker tracker_;
  PoseHold hold_;
  LedHoverFrameRecord last_frame_;
  LedHoverCounts counts_;
  double last_step_t_s_ = 0.0;
};

}  // namespace aperture::planning
