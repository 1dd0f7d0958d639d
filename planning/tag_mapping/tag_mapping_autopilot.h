#pragma once
// The mapping flight of paper D (issue 15, item 3) as a perception::Autopilot: a lawn-mower
// coverage of the tag field (lawn_mower_coverage.h: the height that keeps the smallest tag
// resolvable, tracks with the stated side overlap) flown with the downward camera, whose every
// frame goes through the `apriltag` front end (perception::AprilTagNode in a FrontEndRunner, as
// `aperture run --frontends apriltag` runs it) into an incremental perception::TagMap. The map
// comes from the flight's own images; each image carries the onboard estimate as paper D's do
// (gravity in C from the attitude estimate, and the camera pose in the odometry frame unless
// map_odometry is false).
//
// Flight: hold the first estimated pose for settle_s, then one minimum-jerk MotionPrimitive
// (planning/motion_primitive.h, rest to rest) per straight segment: to the first track's start,
// along each track, across to the next; the heading turns during the first segment to the one
// that puts the footprint's wider image axis across the tracks and then stays. Each segment lasts
// max(min_segment_duration_s, 1.875 L / max_speed_mps) (1.875: the peak-to-mean speed ratio of a
// rest-to-rest minimum-jerk motion). The reference is tracked by control::PositionController on
// the perception::PoseFusion estimate (IMU + the vehicle's odometry source, OnOdometry: a VIO on
// hardware, experiments/missions/tag_mapping_flight.h in SITL). After the last segment it holds
// for settle_s and reports done. The autopilot never sees ground truth.
//
// Frames: W world (z up), B body, C camera (OpenCV, looking down: z_C within 10 deg of -z_B),
// T_BC the camera mount. SI units; times on the sensor clock.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "control/position_controller.h"
#include "control/trajectory_point.h"
#include "control/vehicle_parameters.h"
#include "perception/autopilot.h"
#include "perception/camera/camera_model.h"
#include "perception/estimation/pose_fusion.h"
#include "perception/graph/front_end_runner.h"
#include "perception/tags/tag_front_end.h"
#include "perception/tags/tag_map.h"
#include "planning/motion_primitive.h"
#include "planning/tag_mapping/lawn_mower_coverage.h"

namespace aperture::planning {

struct TagMappingParams {
  // Height rule: the smallest tag spans at least this many pixels (tag36h11's border edge is 8
  // cells: 14 px is 1.75 px a cell; it puts the 90 deg 640 px camera 2.3 m above the `tags`
  // scenario's 0.1 m tags, where the bench maps them).
  double min_tag_side_px = 14.0;
  // Fraction of the footprint's width that adjacent tracks share (lawn_mower_coverage.h).
  double side_overlap = 0.5;
  double max_speed_mps = 1.0;  // peak speed of a segment
  double min_segment_duration_s = 1.5;
  double settle_s = 1.0;     // hold before the first segment and after the last
  int camera_id = 0;         // Frame::camera_id of the downward camera
  bool map_odometry = true;  // images carry the estimate's camera pose (TagMapOnboardEstimate)
  control::PositionControllerParams controller;
  perception::PoseFusionParams fusion;  // set the IMU noise of the vehicle's IMU

  void Validate() const;  // std::invalid_argument naming the field
};

// What the vehicle is told of the field: where it is and which tags lie on what (no positions).
struct TagField {
  FieldRectangle rectangle;
  std::vector<TagClass> classes;  // every tag size on every surface height
  // Edge of the largest tag's whole pattern (white border included) [m]: the footprint margin.
  double max_pattern_m = 0.0;
};

class TagMappingAutopilot : public perception::Autopilot {
 public:
  // Throws std::invalid_argument for invalid params, an empty field, a null camera, a non-rigid
  // T_BC or a camera that does not look down.
  TagMappingAutopilot(const TagMappingParams& params, const TagField& field,
                      std::shared_ptr<const perception::CameraModel> camera,
                      const Eigen::Isometry3d& T_BC, const control::VehicleParameters& vehicle,
                      const perception::TagFrontEndParams& front_end,
                      const perception::TagMapParams& map);

  std::string name() const override { return "tag_mapping"; }
  void OnImu(const perception::ImuSample& sample) override;
  void OnFrame(const perception::Frame& frame) override;
  // A body pose from the vehicle's odometry source (X = B).
  void OnOdometry(const perception::PoseMeasurement& pose_WB);
  perception::AutopilotCommand Step(double t_s) override;
  std::string status() const override;
  // The front end's overlay and, in the lower right corner, the map so far seen from above.
  void DrawOverlay(cv::Mat& bgr) const;

  double height_m() const { return height_m_; }  // of the camera [m]
  const LawnMowerPlan& plan() const { return plan_; }
  perception::TagMap& map() { return map_; }
  const perception::TagMap& map() const { return map_; }
  int frames() const { return frames_; }  // downward-camera frames processed
  int frames_with_tags() const { return frames_with_tags_; }
  // Start and end of the lawn-mower segments [s]; nullopt before the flight starts.
  std::optional<double> flight_start_t_s() const;
  std::optional<double> flight_end_t_s() const;
  bool done() const { return done_; }
  // The time from the first estimate to done for a start at p_WB_start [s] (the camera's offset
  // from B left out of the segment lengths: a few centimetres of a lawn-mower's metres).
  double PlannedDurationS(const Eigen::Vector3d& p_WB_start) const;

 private:
  struct Segment {
    double start_t_s;
    MotionPrimitive position;
    std::optional<MotionPrimitive> heading;  // in x (the first segment's turn)
  };
  std::optional<control::QuadState> Estimate() const;
  double SegmentDurationS(double length_m) const;
  void PlanSegments(double t_s, const control::QuadState& x);
  control::TrajectoryPoint Reference(double t_s) const;

  TagMappingParams params_;
  std::shared_ptr<const perception::CameraModel> camera_;
  Eigen::Isometry3d T_BC_;
  control::VehicleParameters vehicle_;
  double height_m_ = 0.0;
  bool image_x_across_ = true;  // the wider footprint axis is the image's x
  LawnMowerPlan plan_;
  perception::FrontEndRunner front_ends_;
  perception::TagMap map_;
  control::PositionController controller_;
  perception::PoseFusion fusion_;
  std::vector<Segment> segments_;
  double heading_rad_ = 0.0;
  bool done_ = false;
  int frames_ = 0;
  int frames_with_tags_ = 0;
};

}  // namespace aperture::planning
