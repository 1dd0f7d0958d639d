#include "planning/tag_mapping/tag_mapping_autopilot.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "perception/tags/april_tag_node.h"
#include "perception/tags/tag_detector_registry.h"
#include "perception/tags/tag_map_writer.h"

namespace aperture::planning {
namespace {

// Peak over mean speed of a rest-to-rest minimum-jerk motion: p(tau) = L (10 tau^3 - 15 tau^4 +
// 6 tau^5) peaks at tau = 1/2 with 15/8 L / T.
constexpr double kMinimumJerkPeakToMean = 1.875;
// The camera must look within this angle of straight down (-z_B) [deg].
constexpr double kMaxCameraTiltDeg = 10.0;

std::vector<std::unique_ptr<perception::Node>> AprilTagFrontEnd(
    std::shared_ptr<const perception::CameraModel> camera,
    const perception::TagFrontEndParams& params) {
  perception::TagFrontEnd front_end(
      perception::TagDetectorRegistry::WithBuiltins().Create(params.detector, params.detection),
      std::move(camera), params);
  std::vector<std::unique_ptr<perception::Node>> nodes;
  nodes.push_back(
      std::make_unique<perception::AprilTagNode>(std::move(front_end), std::nullopt, ""));
  return nodes;
}

double HeadingOf(const Eigen::Matrix3d& R_WB) { return std::atan2(R_WB(1, 0), R_WB(0, 0)); }

}  // namespace

void TagMappingParams::Validate() const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("TagMappingParams: " + what);
  };
  require(min_tag_side_px > 0.0, "min_tag_side_px must be > 0");
  require(side_overlap >= 0.0 && side_overlap < 1.0, "side_overlap must be in [0, 1)");
  require(max_speed_mps > 0.0, "max_speed_mps must be > 0");
  require(min_segment_duration_s > 0.0, "min_segment_duration_s must be > 0");
  require(settle_s >= 0.0, "settle_s must be >= 0");
  require(camera_id >= 0, "camera_id must be >= 0");
  fusion.Validate();
}

TagMappingAutopilot::TagMappingAutopilot(const TagMappingParams& params, const TagField& field,
                                         std::shared_ptr<const perception::CameraModel> camera,
                                         const Eigen::Isometry3d& T_BC,
                                         const control::VehicleParameters& vehicle,
                                         const perception::TagFrontEndParams& front_end,
                                         const perception::TagMapParams& map)
    : params_((params.Validate(), params)),
      camera_(std::move(camera)),
      T_BC_(T_BC),
      vehicle_(vehicle),
      front_ends_(camera_ ? AprilTagFrontEnd(camera_, front_end)
                          : throw std::invalid_argument(
                                "TagMappingAutopilot: camera is null; pass the downward camera")),
      map_(map),
      controller_(vehicle, params.controller),
      fusion_(params.fusion) {
  perception::RequireRigid(T_BC_, "TagMappingAutopilot T_BC");
  if (T_BC_.linear().col(2).dot(-Eigen::Vector3d::UnitZ()) <
      std::cos(kMaxCameraTiltDeg * M_PI / 180.0)) {
    throw std::invalid_argument(
        "TagMappingAutopilot: the mapping camera does not look down (its z_C is more than 10 deg "
        "off -z_B); mount it looking down");
  }
  if (field.classes.empty()) {
    throw std::invalid_argument("TagMappingAutopilot: the field has no tags to map");
  }
  height_m_ = MappingHeight(CentralFocalLengthPx(*camera_), field.classes, params_.min_tag_side_px);
  double top_m = field.classes.front().surface_height_m;
  for (const TagClass& c : field.classes) top_m = std::max(top_m, c.surface_height_m);
  const Footprint footprint = FootprintAtDepth(*camera_, height_m_ - top_m);
  const double margin_m = field.max_pattern_m / std::sqrt(2.0);
  const double half_x = footprint.half_x_m - margin_m, half_y = footprint.half_y_m - margin_m;
  image_x_across_ = half_x >= half_y;
  plan_ = PlanLawnMower(field.rectangle, height_m_, std::max(half_x, half_y),
                        std::min(half_x, half_y), params_.side_overlap);
}

void TagMappingAutopilot::OnImu(const perception::ImuSample& sample) { fusion_.AddImu(sample); }

void TagMappingAutopilot::OnOdometry(const perception::PoseMeasurement& pose_WB) {
  fusion_.AddPose(pose_WB);
}

std::optional<control::QuadState> TagMappingAutopilot::Estimate() const {
  const std::optional<perception::PoseImuEstimate> e = fusion_.estimate();
  if (!e) return std::nullopt;
  return e->state;
}

void TagMappingAutopilot::OnFrame(const perception::Frame& frame) {
  if (frame.camera_id != params_.camera_id) return;
  ++frames_;
  front_ends_.Process(frame);
  const auto* result =
      front_ends_.Latest<perception::TagFrameResult>(perception::AprilTagNode::kOutputSlot);
  const std::vector<perception::TagMapObservation> observations =
      perception::MapObservations(*result);
  if (!observations.empty()) ++frames_with_tags_;
  perception::TagMapOnboardEstimate onboard;
  if (const std::optional<control::QuadState> x = Estimate()) {
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.linear() = x->q_WB.toRotationMatrix();
    T_WB.translation() = x->p_WB;
    const Eigen::Isometry3d T_WC = T_WB * T_BC_;
    onboard.down_C = T_WC.linear().transpose() * -Eigen::Vector3d::UnitZ();
    if (params_.map_odometry) onboard.T_OC = T_WC;
  }
  map_.AddImage(frame.t_s, observations, onboard);
}

void TagMappingAutopilot::PlanSegments(double t_s, const control::QuadState& x) {
  // The heading that turns the wider footprint axis across the tracks, nearest the current one.
  const double start_heading = HeadingOf(x.q_WB.toRotationMatrix());
  const Eigen::Vector3d axis_B = T_BC_.linear().col(image_x_across_ ? 0 : 1);
  const Eigen::Vector2d& along = plan_.track_direction_W;
  const double heading = std::atan2(along.x(), -along.y()) - std::atan2(axis_B.y(), axis_B.x());
  double turn = std::remainder(heading - start_heading, 2.0 * M_PI);
  if (std::abs(turn) > M_PI / 2) turn -= std::copysign(M_PI, turn);  // the other sign of the axis
  heading_rad_ = start_heading + turn;
  const Eigen::Matrix3d R_WB = Eigen::AngleAxisd(heading_rad_, Eigen::Vector3d::UnitZ()).matrix();

  std::vector<Eigen::Vector3d> points_W{x.p_WB};
  for (const Eigen::Vector3d& p_WC : plan_.camera_waypoints_W) {
    points_W.push_back(p_WC - R_WB * T_BC_.translation());
  }
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  double start_t_s = t_s + params_.settle_s;
  for (std::size_t k = 1; k < points_W.size(); ++k) {
    const double duration_s = SegmentDurationS((points_W[k] - points_W[k - 1]).norm());
    Segment segment{
        start_t_s,
        MotionPrimitive(points_W[k - 1], zero, zero, points_W[k], zero, zero, duration_s),
        std::nullopt};
    if (k == 1) {
      segment.heading =
          MotionPrimitive(Eigen::Vector3d(start_heading, 0, 0), zero, zero,
                          Eigen::Vector3d(heading_rad_, 0, 0), zero, zero, duration_s);
    }
    segments_.push_back(std::move(segment));
    start_t_s += duration_s;
  }
}

double TagMappingAutopilot::SegmentDurationS(double length_m) const {
  return std::max(params_.min_segment_duration_s,
                  kMinimumJerkPeakToMean * length_m / params_.max_speed_mps);
}

double TagMappingAutopilot::PlannedDurationS(const Eigen::Vector3d& p_WB_start) const {
  double duration_s = 2.0 * params_.settle_s;
  Eigen::Vector3d previous = p_WB_start;
  for (const Eigen::Vector3d& p_WC : plan_.camera_waypoints_W) {
    duration_s += SegmentDurationS((p_WC - previous).norm());
    previous = p_WC;
  }
  return duration_s;
}

std::optional<double> TagMappingAutopilot::flight_start_t_s() const {
  if (segments_.empty()) return std::nullopt;
  return segments_.front().start_t_s;
}

std::optional<double> TagMappingAutopilot::flight_end_t_s() const {
  if (segments_.empty()) return std::nullopt;
  return segments_.back().start_t_s + segments_.back().position.duration_s();
}

control::TrajectoryPoint TagMappingAutopilot::Reference(double t_s) const {
  // The segment flown at t_s: the last one that has started (the first before the start).
  auto it = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                             [](double t, const Segment& s) { return t < s.start_t_s; });
  const Segment& segment = it == segments_.begin() ? segments_.front() : *std::prev(it);
  const double t = std::clamp(t_s - segment.start_t_s, 0.0, segment.position.duration_s());
  control::TrajectoryPoint reference = segment.position.Sample(t);
  reference.t_s = t_s;
  reference.heading_rad = heading_rad_;
  if (segment.heading) {
    reference.heading_rad = segment.heading->Position(t).x();
    reference.heading_rate_radps = segment.heading->Velocity(t).x();
    reference.heading_acc_radps2 = segment.heading->Acceleration(t).x();
  }
  return reference;
}

perception::AutopilotCommand TagMappingAutopilot::Step(double t_s) {
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  const std::optional<control::QuadState> x = Estimate();
  if (!x) {  // no odometry yet: level, hover thrust (the SITL starts hovering)
    command.thrust_rates.collective_thrust_mps2 = vehicle_.gravity_mps2;
    return command;
  }
  if (segments_.empty()) PlanSegments(t_s, *x);
  command.thrust_rates = controller_.Compute(*x, Reference(t_s)).command;
  done_ = done_ || t_s >= *flight_end_t_s() + params_.settle_s;
  command.done = done_;
  return command;
}

std::string TagMappingAutopilot::status() const {
  if (segments_.empty()) return "waiting for odometry";
  const double t_s = fusion_.estimate()->state.t_s;
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                                   [](double t, const Segment& s) { return t < s.start_t_s; });
  const int segment = static_cast<int>(it - segments_.begin());
  std::string phase = "segment " + std::to_string(segment) + "/" + std::to_string(segments_.size());
  if (done_) {
    phase = "mapping flight done";
  } else if (segment == 0) {
    phase = "settling";
  } else if (t_s > *flight_end_t_s()) {
    phase = "holding at the end";
  }
  return phase + ", " + std::to_string(map_.Tags().size()) + " tags mapped";
}

void TagMappingAutopilot::DrawOverlay(cv::Mat& bgr) const {
  front_ends_.DrawOverlays(bgr);
  const std::vector<perception::MappedTag> tags = map_.Tags();
  if (tags.empty()) return;
  // The map so far, from above, scaled into the lower right corner.
  perception::TopViewOptions options;
  options.pixels_per_m = 60.0;
  options.margin_m = 0.3;
  cv::Mat view = perception::DrawTagMapTopView(tags, options);
  const double scale = std::min({1.0, 0.45 * bgr.rows / view.rows, 0.4 * bgr.cols / view.cols});
  cv::resize(view, view, cv::Size(), scale, scale, cv::INTER_AREA);
  cv::putText(view, "map: " + std::to_string(tags.size()) + " tags", {4, 14},
              cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  const cv::Rect corner(bgr.cols - view.cols - 4, bgr.rows - view.rows - 4, view.cols, view.rows);
  if (corner.x < 0 || corner.y < 0) return;
  view.copyTo(bgr(corner));
  cv::rectangle(bgr, corner, cv::Scalar(0, 255, 255), 1);
}

}  // namespace aperture::planning
