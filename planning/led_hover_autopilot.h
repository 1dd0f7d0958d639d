#pragma once
// LED-stabilized hover (Faessler thesis, Appendix C.4.3): a camera fixed in the world (e.g. on
// a ground robot, pose T_WC) observes the infrared LEDs on the vehicle (target frame T, mounted at
// T_BT in the body). Every frame goes through the `led` front end (perception::LedTrackerNode,
// the node `aperture run --frontends led` runs) inside a perception::FrontEndRunner; its pose
// observation T_CT (fixed camera) goes through perception::ToPoseMeasurement with the rig
// {T_WC, T_BT} into PoseHold (pose fusion + position control at the set-point). Only the LED pose
// and the IMU are used: this runs on hardware (frames from the ground camera's link, IMU from the
// flight controller) as in SITL. Frames: T_WB = T_WC * T_CT * T_BT^-1.
#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "perception/autopilot.h"
#include "perception/camera/camera_model.h"
#include "perception/estimation/pose_fusion.h"
#include "perception/graph/front_end_runner.h"
#include "perception/led/led_configuration.h"
#include "perception/led/led_tracker.h"
#include "planning/pose_hold.h"

namespace aperture::planning {

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
  Eigen::Vector3d p_WB = Eigen::Vector3d::Zero();  // measured body position (has_pose)
  perception::PoseFusionOutcome update;            // (has_pose)
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
  // The LED front end of the latest frame (overlay video).
  const perception::FrontEndRunner& front_ends() const { return front_ends_; }
  // The latest LED-camera frame (for logs: a driver reads it after each OnFrame).
  const LedHoverFrameRecord& last_frame() const { return last_frame_; }
  const LedHoverCounts& counts() const { return counts_; }

 private:
  LedHoverAutopilotParams params_;
  perception::FrontEndRunner front_ends_;
  perception::PoseRig rig_;
  PoseHold hold_;
  LedHoverFrameRecord last_frame_;
  LedHoverCounts counts_;
  double last_step_t_s_ = 0.0;
};

}  // namespace aperture::planning
