#pragma once
// Paper D's quadrotor watching the ground robot (seed 001, Sec. D.6: it "follows the ground robot
// to relocalize it"), issue 16 item 3, as a perception::Autopilot: image-based visual servoing
// on the four corners of the robot's tag (servo::PointServo, ViSP vpFeaturePoint with the
// target-motion feed-forward) keeps the tag centred below the downward camera at follow_height_m
// and turns the vehicle with the robot, while the robot drives.
//
// Phases: settle (hold the first estimate for settle_s) -> search (one minimum-jerk segment to
// search_xy_W at search_height_m, where the camera sees the whole field; MotionPrimitive) ->
// follow as soon as the tag is found, from any phase. In follow every frame with the tag gives
// one servo step: corners undistorted through the camera model, re-projected into the level
// camera with the attitude estimate (servo/level_view.h), depth = the tag centre's depth in
// the level camera from the tag's pose (perception/tags/tag_pose_estimator.h). The body velocity
// reference (capped at max_speed_mps) and yaw rate go to control::PositionController as a
// velocity reference (planning/body_velocity_tracking.h). Without the tag for lost_timeout_s the
// vehicle stops where it is ("lost") and follows again when the tag reappears. The autopilot never
// reports done: it watches the robot until the run ends.
//
// State estimation as the mapping flight: perception::PoseFusion of the IMU and the vehicle's
// odometry source (OnOdometry). Never sees ground truth.
//
// Frames: W world (z up), B body, C camera (OpenCV, looking down), T tag (x right, y down, z into
// the tag: tag_detector.h). The goal view: the tag centred, x_T along x_C (R_CT = I), at depth
// follow_height_m, up to the quarter turn nearest the tag's rotation (point IBVS retreats from a
// target turned by ~pi). SI units; times on the sensor clock.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "control/position_controller.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"
#include "perception/camera/camera_model.h"
#include "perception/estimation/pose_fusion.h"
#include "perception/tags/tag_front_end.h"
#include "planning/motion_primitive.h"
#include "servo/point_servo.h"

namespace aperture::planning {

struct TagFollowParams {
  int target_id = 2;             // the robot's tag (scenario `tags`: 2), family of the front end
  double follow_height_m = 1.8;  // camera above the tag while following [m]
  double search_height_m = 4.0;  // camera height while searching [m]
  double max_speed_mps = 1.0;    // cap of the servo's velocity reference [m/s]
  // Rate limit of the velocity reference [m/s^2]: a robot that starts at full speed would
  // otherwise make the vehicle tilt ~8 deg to catch up, which alone moves the tag 7 % of the
  // image width (tan(tilt) / 2 for a 90 deg camera). The servo's target-motion estimate takes the
  // vehicle's measured motion (PointServo::Step own_motion), so the limit does not corrupt it.
  double max_accel_mps2 = 1.0;
  double search_speed_mps = 1.0;  // peak speed of the search segment [m/s]
  double settle_s = 1.0;
  double lost_timeout_s = 1.0;  // without the tag this long: stop [s]
  // Locked on: the servo error |s - s*| (8 normalized coordinates) stays below lock_error for
  // lock_hold_s (0.05: ~1 px per coordinate at f = 160 px) — the robot may start driving.
  double lock_error = 0.05;
  double lock_hold_s = 1.0;
  int camera_id = 0;  // Frame::camera_id of the downward camera
  servo::PointServoParams servo;
  control::PositionControllerParams controller;
  perception::PoseFusionParams fusion;  // set the IMU noise of the vehicle's IMU

  void Validate() const;  // std::invalid_argument naming the field
};

// `mission` keys as the field names; `servo` as servo/servo_params_io.h's `tag_servo`.
void LoadParams(config::ParamReader& reader, TagFollowParams* params);

enum class TagFollowPhase { kSettle, kSearch, kFollow, kLost };
const char* ToString(TagFollowPhase phase);

// One downward-camera frame, for plots and the evaluation.
struct TagFollowSample {
  double t_s = 0.0;
  bool target_seen = false;
  Eigen::Vector2d target_center_px = Eigen::Vector2d::Zero();  // mean of the corners
  double servo_error = 0.0;                                    // |s - s*| (0 without a step)
  Eigen::Vector3d v_B = Eigen::Vector3d::Zero();               // the capped reference [m/s]
  double yaw_rate_radps = 0.0;
  // The target tag's pose in W from this frame (the tag's pose in the camera through the state
  // estimate): what relocalizes the ground robot (paper D Sec. D.6). nullopt without the tag
  // or an estimate.
  std::optional<Eigen::Isometry3d> T_WT;
};

class TagFollowAutopilot : public perception::Autopilot {
 public:
  // target_size_m: the edge of the robot tag's black border. Throws std::invalid_argument for
  // invalid params or size, a null camera, a non-rigid T_BC or a camera that does not look down.
  TagFollowAutopilot(const TagFollowParams& params, double target_size_m,
                     const Eigen::Vector2d& search_xy_W,
                     std::shared_ptr<const perception::CameraModel> camera,
                     const Eigen::Isometry3d& T_BC, const control::VehicleParameters& vehicle,
                     const perception::TagFrontEndParams& front_end);

  std::string name() const override { return "tag_follow"; }
  void OnImu(const perception::ImuSample& sample) override;
  void OnFrame(const perception::Frame& frame) override;
  void OnOdometry(const perception::PoseMeasurement& pose_WB);
  perception::AutopilotCommand Step(double t_s) override;
  std::string status() const override;
  // The target's corners (green when servoed), the goal square and the image centre.
  void DrawOverlay(cv::Mat& bgr) const;

  TagFollowPhase phase() const { return phase_; }
  const std::vector<TagFollowSample>& trace() const { return trace_; }
  // Sensor time the tag was first found [s]; nullopt before.
  std::optional<double> first_seen_t_s() const { return first_seen_t_s_; }
  // Sensor time the follower first locked on (see lock_error) [s]; nullopt before.
  std::optional<double> locked_t_s() const { return locked_t_s_; }

 private:
  std::optional<control::QuadState> Estimate() const;
  perception::AutopilotCommand Command(const control::QuadState& x,
                                       const control::TrajectoryPoint& reference) const;
  void ServoOn(const perception::TagResult& tag, double t_s, const control::QuadState& x);

  TagFollowParams params_;
  double target_size_m_;
  Eigen::Vector2d search_xy_W_;
  std::shared_ptr<const perception::CameraModel> camera_;
  Eigen::Isometry3d T_BC_;
  control::VehicleParameters vehicle_;
  perception::TagFrontEnd front_end_;
  servo::PointServo servo_;
  control::PositionController controller_;
  perception::PoseFusion fusion_;

  TagFollowPhase phase_ = TagFollowPhase::kSettle;
  double phase_start_t_s_ = 0.0;
  bool started_ = false;
  Eigen::Vector3d hold_p_W_ = Eigen::Vector3d::Zero();
  double heading_rad_ = 0.0;  // the reference heading (integrated yaw rate while following)
  double last_step_t_s_ = 0.0;
  std::optional<MotionPrimitive> search_;
  std::optional<double> first_seen_t_s_;
  double last_seen_t_s_ = -1e9;
  std::optional<double> below_lock_since_t_s_;
  std::optional<double> locked_t_s_;
  servo::BodyVelocityReference reference_;             // the latest servo step's, capped
  Eigen::Vector3d v_ref_W_ = Eigen::Vector3d::Zero();  // rate-limited towards reference_ [m/s]
  double servo_error_ = 0.0;                           // its |s - s*|
  std::vector<TagFollowSample> trace_;
  std::optional<std::array<Eigen::Vector2d, 4>> last_corners_px_;
  servo::PointServo::Corners desired_;  // the goal view's corners (normalized, level camera)
  int corner_shift_ = 0;                // goal corner k is seen corner (k + shift) % 4
};

}  // namespace aperture::planning
