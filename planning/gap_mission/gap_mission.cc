#include "planning/gap_mission/gap_mission.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "control/height_filter.h"
#include "control/require.h"
#include "control/so3.h"
#include "perception/gap/gap_node.h"

namespace aperture::planning {
namespace {

double HeadingOf(const Eigen::Quaterniond& q_WB) {
  const Eigen::Vector3d x_B = q_WB * Eigen::Vector3d::UnitX();
  return std::atan2(x_B.y(), x_B.x());
}

}  // namespace

void GapMissionParams::Validate() const {
  perception::ValidateGapDetectorParams(detector);
  filter.Validate();
  traverse.Validate();
  approach.Validate();
  controller.Validate();
  fallback_limits.Validate();
  recovery.Validate();
  control::RequireAtLeast(camera_id, 0, "GapMissionParams.camera_id");
  control::RequireAtLeast(init_detections, 1, "GapMissionParams.init_detections");
  control::RequireAtLeast(gravity_samples, 1, "GapMissionParams.gravity_samples");
  control::RequireNonNegative(hover_s, "GapMissionParams.hover_s");
  control::RequirePositive(init_max_relative_sigma, "GapMissionParams.init_max_relative_sigma");
  control::RequirePositive(detection_covariance_scale,
                           "GapMissionParams.detection_covariance_scale");
  control::RequireNonNegative(min_ground_clearance_m, "GapMissionParams.min_ground_clearance_m");
  control::RequireAtLeast(max_consecutive_rejections, 1,
                          "GapMissionParams.max_consecutive_rejections");
  control::RequirePositive(transfer_speed_mps, "GapMissionParams.transfer_speed_mps");
  control::RequirePositive(min_transfer_s, "GapMissionParams.min_transfer_s");
  control::RequireNonNegative(start_hold_s, "GapMissionParams.start_hold_s");
  control::RequireNonNegative(lead_in_s, "GapMissionParams.lead_in_s");
  control::RequireNonNegative(min_replan_remaining_s, "GapMissionParams.min_replan_remaining_s");
  control::RequirePositive(detection_timeout_s, "GapMissionParams.detection_timeout_s");
  control::RequireNonNegative(approach_commit_s, "GapMissionParams.approach_commit_s");
  control::RequireNonNegative(recovered_hold_s, "GapMissionParams.recovered_hold_s");
  control::RequireNonNegative(recovery_odometry_delay_s,
                              "GapMissionParams.recovery_odometry_delay_s");
  perception::RequireProcessNoiseScale(recovery_max_process_noise_scale,
                                       "GapMissionParams.recovery_max_process_noise_scale");
  control::Require(recovery_odometry_alignment_poses >= 1,
                   "GapMissionParams.recovery_odometry_alignment_poses",
                   recovery_odometry_alignment_poses, "must be >= 1");
  control::RequirePositive(recovery_odometry_velocity_sigma_mps,
                           "GapMissionParams.recovery_odometry_velocity_sigma_mps");
  if (!(recovery_range_sigma_m > 0.0)) {  // +inf allowed (range not fused)
    throw std::invalid_argument(
        "GapMissionParams.recovery_range_sigma_m = " + std::to_string(recovery_range_sigma_m) +
        " must be > 0 (+infinity: the range is not fused)");
  }
}

const char* ToString(GapMissionPhase phase) {
  switch (phase) {
    case GapMissionPhase::kDetect:
      return "detect";
    case GapMissionPhase::kHover:
      return "hover";
    case GapMissionPhase::kTransfer:
      return "transfer";
    case GapMissionPhase::kApproach:
      return "approach";
    case GapMissionPhase::kLeadIn:
      return "lead_in";
    case GapMissionPhase::kTraverse:
      return "traverse";
    case GapMissionPhase::kRecover:
      return "recover";
    case GapMissionPhase::kDone:
      return "done";
    case GapMissionPhase::kAborted:
      return "aborted";
  }
  return "unknown";
}

namespace {

std::vector<std::unique_ptr<perception::Node>> GapFrontEnd(
    const perception::GapDetectorParams& params,
    std::shared_ptr<const perception::CameraModel> camera) {
  if (!camera) throw std::invalid_argument("GapMission: the camera model is null");
  std::vector<std::unique_ptr<perception::Node>> nodes;
  nodes.push_back(std::make_unique<perception::GapNode>(params, std::move(camera)));
  return nodes;
}

}  // namespace

GapMission::GapMission(const GapMissionParams& params,
                       std::shared_ptr<const perception::CameraModel> camera,
                       const Eigen::Isometry3d& T_BC, const control::VehicleParameters& vehicle)
    : params_((params.Validate(), params)),
      T_BC_((perception::RequireRigid(T_BC, "GapMission: T_BC (camera mount)"), T_BC)),
      vehicle_(vehicle),
      front_ends_(GapFrontEnd(params.detector, std::move(camera))),
      approach_planner_(params.approach),
      controller_(vehicle, params.controller),
      attitude_controller_(params.controller.attitude),
      attitude_hold_(params.controller.attitude),
      recovery_(vehicle, params.recovery),
      rig_{Eigen::Isometry3d::Identity(), T_BC, params.detection_covariance_scale},
      fusion_({params.filter, params.max_consecutive_rejections}) {
  recent_up_B0_.reserve(static_cast<std::size_t>(params_.gravity_samples));
  phase_changes_.push_back({0.0, phase_});
}

void GapMission::EnterPhase(GapMissionPhase phase, double t_s) {
  phase_ = phase;
  phase_start_t_s_ = t_s;
  phase_changes_.push_back({t_s, phase});
}

void GapMission::Abort(const std::string& reason, double t_s) {
  reason_ = reason;
  EnterPhase(GapMissionPhase::kAborted, t_s);
  StartRecovery(t_s);
}

void GapMission::StartRecovery(double t_s) {
  recovery_.StartWithoutLaunch(t_s);
  recovery_start_t_s_ = t_s;
}

void GapMission::OnImu(const perception::ImuSample& sample) {
  if (!fusion_.started()) attitude_hold_.AddImu(sample.t_s, sample.omega_B);
  last_imu_ = sample;
  fusion_.AddImu(sample);
  if (fusion_.started()) return;
  // Hovering at rest before the filter starts: the specific force is gravity, up in B; kept in
  // B0 so that samples taken while the vehicle turned average in one frame.
  const Eigen::Vector3d up_B0 = attitude_hold_.q_B0B() * sample.specific_force_B.normalized();
  if (recent_up_B0_.size() < static_cast<std::size_t>(params_.gravity_samples)) {
    recent_up_B0_.push_back(up_B0);
  } else {
    recent_up_B0_[recent_up_next_] = up_B0;
    recent_up_next_ = (recent_up_next_ + 1) % recent_up_B0_.size();
  }
}

bool GapMission::LookingForGap(double frame_t_s) const {
  // The detector looks until the planned crossing of the gap plane; after it the gap is behind.
  switch (phase_) {
    case GapMissionPhase::kDetect:
    case GapMissionPhase::kHover:
    case GapMissionPhase::kTransfer:
    case GapMissionPhase::kApproach:
    case GapMissionPhase::kLeadIn:
      return true;
    case GapMissionPhase::kTraverse:
      return frame_t_s < traverse_start_t_s_ + traverse_->time_to_gap_s();
    default:
      return false;
  }
}

bool GapMission::WantsFrame(int camera_id, double t_s) const {
  return camera_id == params_.camera_id && LookingForGap(t_s);
}

void GapMission::OnFrame(const perception::Frame& frame) {
  if (!WantsFrame(frame.camera_id, frame.t_s)) return;
  const std::vector<perception::PoseObservation>& observations = front_ends_.Process(frame);
  last_detection_ = *front_ends_.Latest<perception::GapDetection>(perception::GapNode::kOutputSlot);
  last_frame_t_s_ = frame.t_s;
  ++frames_processed_;
  for (perception::PoseObservation observation : observations) {
    if (observation.stream != perception::GapNode::kName) continue;
    ++detections_;
    last_detected_t_s_ = frame.t_s;
    if (!fusion_.started()) {
      last_T_CG_ = observation.T_CX;
      AccumulateUpInGap(last_T_CG_);
      continue;
    }
    // The gap is fixed in W: its labelling follows the estimate, not the image's convention.
    const Eigen::Matrix3d R_WC = estimate().q_WB.toRotationMatrix() * T_BC_.linear();
    observation.T_CX = perception::NearestGapLabelling(observation.T_CX,
                                                       R_WC.transpose() * rig_.T_W_fixed.linear());
    // A frame stamped after the latest IMU sample (IMU latency) waits for the IMU to catch up.
    fusion_.AddPose(perception::ToPoseMeasurement(observation, rig_));
  }
}

void GapMission::AccumulateUpInGap(const Eigen::Isometry3d& T_CG) {
  if (recent_up_B0_.empty()) return;  // no IMU yet: gravity unknown
  Eigen::Vector3d up_B0 = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& u : recent_up_B0_) up_B0 += u;
  // In the body of this detection:
  const Eigen::Vector3d up_B = attitude_hold_.q_B0B().conjugate() * up_B0;
  const Eigen::Matrix3d R_GB = T_CG.linear().transpose() * T_BC_.linear().transpose();
  up_G_sum_ += R_GB * up_B.normalized();
}

void GapMission::OnRange(const perception::RangeReading& reading) {
  if (!reading.valid || !fusion_.started()) return;
  const control::QuadState x = estimate();
  const double cos_tilt = (x.q_WB * Eigen::Vector3d::UnitZ()).z();
  if (cos_tilt < std::cos(params_.recovery.max_tilt_for_height_rad)) return;
  const std::optional<double> height_m =
      control::HeightFilter::HeightFromRange(reading.range_m, x.q_WB);
  if (!height_m) return;
  if (std::isnan(recovery_start_t_s_)) {
    // Floor samples while the gap is tracked; the estimate sharpens on the way in, so the mean
    // forgets (kFloorWeight ~ the last 20 readings): a floor fixed far from the gap carried the
    // hover's height error (~9 cm in SITL) into every recovery height.
    if (phase_ == GapMissionPhase::kDetect || phase_ == GapMissionPhase::kTraverse) return;
    constexpr double kFloorWeight = 0.05;
    const double floor_sample_m = x.p_WB.z() - *height_m;
    ++floor_samples_;
    const double weight = std::max(kFloorWeight, 1.0 / floor_samples_);
    floor_z_W_ =
        floor_z_W_ ? *floor_z_W_ + weight * (floor_sample_m - *floor_z_W_) : floor_sample_m;
    return;
  }
  if (!floor_z_W_ || std::isinf(params_.recovery_range_sigma_m)) return;
  const double sigma_m = params_.recovery_range_sigma_m;
  fusion_.AddHeight({reading.t_s, *floor_z_W_ + *height_m, sigma_m * sigma_m});
}

void GapMission::OnOdometry(const perception::PoseMeasurement& pose_OB) {
  if (std::isnan(recovery_start_t_s_) || !fusion_.started() ||
      !(pose_OB.t_s >= recovery_start_t_s_ + params_.recovery_odometry_delay_s)) {
    return;
  }
  if (!T_WO_) {
    // O placed so that the odometry's poses are the estimate's, rotation included: W is only as
    // gravity-aligned as the accelerometer average that fixed it (a bias tilts it), so aligning
    // the heading alone would leave an attitude innovation the filter gates out, then restarts on.
    const control::QuadState x = estimate();
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.linear() = x.q_WB.toRotationMatrix();
    T_WB.translation() = x.p_WB;
    Eigen::Isometry3d T_OB = Eigen::Isometry3d::Identity();
    T_OB.linear() = perception::BodyOrientation(pose_OB).toRotationMatrix();
    T_OB.translation() = perception::BodyPosition(pose_OB);
    if (odometry_alignments_.empty()) odometry_alignment_start_ = fusion_.estimate();
    odometry_alignments_.emplace_back(pose_OB, T_WB * T_OB.inverse());
    if (static_cast<int>(odometry_alignments_.size()) < params_.recovery_odometry_alignment_poses) {
      return;
    }
    std::vector<Eigen::Quaterniond> q_WO;
    Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();
    for (const auto& alignment : odometry_alignments_) {
      q_WO.emplace_back(alignment.second.linear());
      p_WO += alignment.second.translation();
    }
    T_WO_ = Eigen::Isometry3d::Identity();
    T_WO_->linear() = control::MeanRotation(q_WO).toRotationMatrix();
    T_WO_->translation() = p_WO / static_cast<double>(odometry_alignments_.size());
    // The hold before done counts on the vision-based estimate ("locks to a hover position").
    if (!std::isnan(position_stage_since_t_s_)) position_stage_since_t_s_ = pose_OB.t_s;
    // Start again where the first averaged pose arrived (the IMU buffer permitting), the
    // velocity widened (recovery_odometry_velocity_sigma_mps), and fuse the averaged poses after
    // that start, oldest first; the last is pose_OB, fused below.
    perception::PoseImuEstimate start = *odometry_alignment_start_;
    const perception::PoseImuEstimate now = *fusion_.estimate();
    if (start.state.t_s < now.state.t_s - params_.filter.history_duration_s) start = now;
    const double sigma_v = params_.recovery_odometry_velocity_sigma_mps;
    start.covariance.block<3, 3>(perception::ErrorStateIndex::kVelocity,
                                 perception::ErrorStateIndex::kVelocity) +=
        sigma_v * sigma_v * Eigen::Matrix3d::Identity();
    fusion_.Start(start);
    odometry_alignments_.pop_back();
    for (const auto& alignment : odometry_alignments_) {
      if (alignment.first.t_s <= start.state.t_s) continue;
      fusion_.AddPose(perception::InWorldFrame(*T_WO_, alignment.first));
      ++odometry_poses_fused_;
    }
    odometry_alignments_.clear();
    odometry_alignment_start_.reset();
    fusion_.AdaptProcessNoise(params_.recovery_max_process_noise_scale);
  }
  fusion_.AddPose(perception::InWorldFrame(*T_WO_, pose_OB));
  ++odometry_poses_fused_;
}

void GapMission::StartFilter() {
  // Mission frame in G: z_W = up, x_W = horizontal part of z_G, y_W = z_W x x_W.
  const Eigen::Vector3d up_G = up_G_sum_.normalized();
  const Eigen::Vector3d z_G = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d x_G_of_W = (z_G - z_G.dot(up_G) * up_G).normalized();
  Eigen::Matrix3d R_GW;
  R_GW.col(0) = x_G_of_W;
  R_GW.col(1) = up_G.cross(x_G_of_W);
  R_GW.col(2) = up_G;
  rig_.T_W_fixed = Eigen::Isometry3d::Identity();
  rig_.T_W_fixed.linear() = R_GW.transpose();  // T_WG
  gap_W_.p_WG.setZero();
  gap_W_.R_WG = rig_.T_W_fixed.linear();
  const Eigen::Isometry3d T_WB = rig_.T_W_fixed * last_T_CG_.inverse() * T_BC_.inverse();
  control::QuadState initial;
  initial.t_s = last_imu_->t_s;
  initial.p_WB = T_WB.translation();
  initial.q_WB = Eigen::Quaterniond(T_WB.linear()).normalized();
  fusion_.Start(initial);
  hover_reference_ = control::TrajectoryPoint();
  hover_reference_.p_W = initial.p_WB;
  hover_reference_.heading_rad = HeadingOf(initial.q_WB);
}

control::QuadState GapMission::estimate() const {
  if (!fusion_.started()) return control::QuadState();
  return fusion_.estimate()->state;
}

double GapMission::position_sigma_m() const {
  if (!fusion_.started()) return std::numeric_limits<double>::quiet_NaN();
  const perception::Matrix15d P = fusion_.estimate()->covariance;
  return std::sqrt(
      P.block<3, 3>(perception::ErrorStateIndex::kPosition, perception::ErrorStateIndex::kPosition)
          .diagonal()
          .maxCoeff());
}

void GapMission::Plan(double t_s) {
  const TraverseOptimizationResult traverse = OptimizeTraverseTrajectory(gap_W_, params_.traverse);
  if (traverse.status != TraverseOptimizationResult::Status::kSuccess) {
    Abort("traverse optimization failed (" +
              std::string(traverse.status == TraverseOptimizationResult::Status::kInfeasible
                              ? "infeasible"
                              : "solver failure") +
              ")",
          t_s);
    return;
  }
  // The approach ends lead_in_s before the traverse start, on the traverse arc.
  ApproachTarget target = ApproachTarget::FromTraverse(*traverse.trajectory);
  target.p_W = traverse.trajectory->Position(-params_.lead_in_s);
  target.v_W = traverse.trajectory->Velocity(-params_.lead_in_s);
  ApproachPlannerParameters approach_params = params_.approach;
  if (floor_z_W_) approach_params.min_height_m = *floor_z_W_ + params_.min_ground_clearance_m;
  approach_planner_ = ApproachPlanner(approach_params);
  ApproachPlan plan = approach_planner_.Plan(target);
  if (!plan.best) {
    // Steep gaps: the fallback limits, to the traverse start itself (no lead-in, as the paper).
    // On the arc the vehicle decelerates at |g_Pi| (~8 m/s^2 at 55 deg roll), so ending the
    // approach lead_in_s earlier asks it to be ~1.6 m/s faster there: beyond 55 deg roll no
    // candidate then passed even these limits, and below, the approach's last rotation still
    // ringing through the lead-in left the crossings 4 cm off where without it they were 1.5 cm
    // (SITL, 45-60 deg roll, 20 trials each).
    used_fallback_limits_ = true;
    target = ApproachTarget::FromTraverse(*traverse.trajectory);
    approach_params.limits = params_.fallback_limits;
    approach_planner_ = ApproachPlanner(approach_params);
    plan = approach_planner_.Plan(target);
  }
  if (!plan.best) {
    Abort("no feasible approach candidate", t_s);
    return;
  }
  traverse_ = traverse.trajectory;
  approach_target_ = target;
  approach_ = plan.best;
  primitive_ = plan.best->primitive;
  const control::QuadState x = estimate();
  const Eigen::Vector3d start_W = primitive_.initial_position_W();
  const double distance_m = (start_W - x.p_WB).norm();
  const double duration_s =
      std::max(params_.min_transfer_s, 1.875 * distance_m / params_.transfer_speed_mps);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  transfer_ = MotionPrimitive(x.p_WB, x.v_W, zero, start_W, zero, zero, duration_s);
  EnterPhase(GapMissionPhase::kTransfer, t_s);
}

perception::AutopilotCommand GapMission::Track(const control::TrajectoryPoint& reference) const {
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = controller_.Compute(estimate(), reference).command;
  return command;
}

perception::AutopilotCommand GapMission::HoverCommand() const {
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = attitude_hold_.Command(vehicle_.gravity_mps2);
  return command;
}

control::RecoveryInputs GapMission::RecoveryInputsAt(double t_s) const {
  const control::QuadState x = estimate();
  control::RecoveryInputs inputs;
  inputs.t_s = t_s;
  inputs.launch_detected = true;
  inputs.q_WB = x.q_WB;
  inputs.omega_B = x.omega_B;
  // The filter's height is relative to the gap centre, which only offsets the held height.
  control::HeightEstimate height;
  height.z_m = x.p_WB.z();
  height.z_dot_mps = x.v_W.z();
  height.time_since_init_s = std::max(0.0, t_s - phase_changes_.front().t_s);
  inputs.height = height;
  inputs.vision_state = x;
  return inputs;
}

perception::AutopilotCommand GapMission::Step(double t_s) {
  for (;;) {
    std::optional<perception::AutopilotCommand> command;
    switch (phase_) {
      case GapMissionPhase::kDetect:
        command = StepDetect(t_s);
        break;
      case GapMissionPhase::kHover:
        command = StepHover(t_s);
        break;
      case GapMissionPhase::kTransfer:
        command = StepTransfer(t_s);
        break;
      case GapMissionPhase::kApproach:
        command = StepApproach(t_s);
        break;
      case GapMissionPhase::kLeadIn:
        command = StepLeadIn(t_s);
        break;
      case GapMissionPhase::kTraverse:
        command = StepTraverse(t_s);
        break;
      case GapMissionPhase::kRecover:
      case GapMissionPhase::kDone:
      case GapMissionPhase::kAborted:
        command = StepRecovery(t_s);
        break;
    }
    if (command) return *command;
  }
}

std::optional<perception::AutopilotCommand> GapMission::StepDetect(double t_s) {
  if (up_G_sum_.norm() > 0.0 && detections_ >= params_.init_detections && last_imu_) {
    StartFilter();
    EnterPhase(GapMissionPhase::kHover, t_s);
    return Track(hover_reference_);
  }
  return HoverCommand();
}

std::optional<perception::AutopilotCommand> GapMission::StepHover(double t_s) {
  if (t_s - last_detected_t_s_ > params_.detection_timeout_s) {
    Abort("gap lost while hovering", t_s);
    return std::nullopt;
  }
  const double distance_m = (estimate().p_WB - gap_W_.p_WG).norm();
  if (t_s - phase_start_t_s_ >= params_.hover_s &&
      position_sigma_m() <= params_.init_max_relative_sigma * distance_m) {
    Plan(t_s);  // enters kTransfer, or aborts
    return std::nullopt;
  }
  hover_reference_.t_s = t_s;
  return Track(hover_reference_);
}

std::optional<perception::AutopilotCommand> GapMission::StepTransfer(double t_s) {
  if (t_s - last_detected_t_s_ > params_.detection_timeout_s) {
    Abort("gap lost during the transfer", t_s);
    return std::nullopt;
  }
  const double t_rel = t_s - phase_start_t_s_;
  if (t_rel >= transfer_.duration_s() + params_.start_hold_s) {
    EnterPhase(GapMissionPhase::kApproach, t_s);
    approach_start_t_s_ = t_s;
    approach_end_t_s_ = t_s + primitive_.duration_s();
    primitive_start_t_s_ = t_s;
    last_reference_a_W_.setZero();
    return std::nullopt;
  }
  control::TrajectoryPoint reference = approach_planner_.Sample(
      transfer_, approach_target_.gap_center_W, std::min(t_rel, transfer_.duration_s()));
  reference.t_s = t_s;
  return Track(reference);
}

std::optional<perception::AutopilotCommand> GapMission::StepApproach(double t_s) {
  if (t_s >= approach_end_t_s_) {
    EnterPhase(GapMissionPhase::kLeadIn, t_s);
    return std::nullopt;
  }
  const double remaining_s = approach_end_t_s_ - t_s;
  if (remaining_s > params_.approach_commit_s &&
      t_s - last_detected_t_s_ > params_.detection_timeout_s) {
    Abort("gap lost during the approach", t_s);
    return std::nullopt;
  }
  if (remaining_s > params_.min_replan_remaining_s) {
    const control::QuadState x = estimate();
    const ApproachCandidate candidate =
        approach_planner_.Replan(approach_target_, x.p_WB, x.v_W, last_reference_a_W_, remaining_s);
    if (candidate.IsValid()) {
      primitive_ = candidate.primitive;
      primitive_start_t_s_ = t_s;
      ++replans_accepted_;
    } else {
      ++replans_rejected_;
    }
  }
  control::TrajectoryPoint reference = approach_planner_.Sample(
      primitive_, approach_target_.gap_center_W, t_s - primitive_start_t_s_);
  reference.t_s = t_s;
  last_reference_a_W_ = reference.a_W;
  return Track(reference);
}

std::optional<perception::AutopilotCommand> GapMission::StepLeadIn(double t_s) {
  // Traverse time runs from -LeadInS() at the approach end.
  const double t_traverse = t_s - approach_end_t_s_ - LeadInS();
  if (t_traverse >= 0.0) {
    EnterPhase(GapMissionPhase::kTraverse, t_s);
    traverse_start_t_s_ = t_s;
    traverse_start_estimate_ = estimate();
    return std::nullopt;
  }
  control::TrajectoryPoint reference = traverse_->Sample(t_traverse);
  reference.t_s = t_s;
  return Track(reference);
}

std::optional<perception::AutopilotCommand> GapMission::StepTraverse(double t_s) {
  if (t_s - traverse_start_t_s_ >= traverse_->duration_s()) {
    EnterPhase(GapMissionPhase::kRecover, t_s);
    StartRecovery(t_s);
    return std::nullopt;
  }
  // Open loop: constant thrust, constant attitude (thrust along +-e3, traverse heading).
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates.collective_thrust_mps2 = traverse_->collective_thrust_mps2();
  command.thrust_rates.omega_des_B =
      attitude_controller_
          .Compute(estimate().q_WB, traverse_->thrust_direction_W(), traverse_->heading_rad())
          .omega_fb_B;
  return command;
}

perception::AutopilotCommand GapMission::StepRecovery(double t_s) {
  const control::RecoveryOutput output = recovery_.Step(RecoveryInputsAt(t_s));
  if (output.stage == control::RecoveryStage::kPosition) {
    if (std::isnan(position_stage_since_t_s_)) position_stage_since_t_s_ = t_s;
  } else {
    position_stage_since_t_s_ = std::numeric_limits<double>::quiet_NaN();
  }
  const bool recovered = !std::isnan(position_stage_since_t_s_) &&
                         t_s - position_stage_since_t_s_ >= params_.recovered_hold_s;
  if (recovered && phase_ == GapMissionPhase::kRecover) {
    EnterPhase(GapMissionPhase::kDone, t_s);
  }
  perception::AutopilotCommand command;
  command.kind = perception::AutopilotCommand::Kind::kThrustRates;
  command.thrust_rates = output.command;
  command.done = recovered;
  return command;
}

std::string GapMission::status() const {
  char buffer[160];
  const double t_rel = (fusion_.started() ? fusion_.estimate()->state.t_s : 0.0) - phase_start_t_s_;
  switch (phase_) {
    case GapMissionPhase::kDetect:
      std::snprintf(buffer, sizeof(buffer), "detect (%d/%d detections)", detections_,
                    params_.init_detections);
      return buffer;
    case GapMissionPhase::kTransfer:
      std::snprintf(buffer, sizeof(buffer), "transfer %.1f/%.1f s", t_rel, transfer_.duration_s());
      return buffer;
    case GapMissionPhase::kApproach:
      std::snprintf(buffer, sizeof(buffer), "approach %.2f/%.2f s (%d replans)", t_rel,
                    approach_end_t_s_ - approach_start_t_s_, replans_accepted_);
      return buffer;
    case GapMissionPhase::kTraverse:
      std::snprintf(buffer, sizeof(buffer), "traverse (open loop) %.2f/%.2f s", t_rel,
                    traverse_->duration_s());
      return buffer;
    case GapMissionPhase::kRecover:
    case GapMissionPhase::kDone:
      return std::string(ToString(phase_)) + ": " + control::ToString(recovery_.stage());
    case GapMissionPhase::kAborted:
      return "aborted (" + reason_ + "): " + control::ToString(recovery_.stage());
    case GapMissionPhase::kHover:
    case GapMissionPhase::kLeadIn:
      break;
  }
  return ToString(phase_);
}

}  // namespace aperture::planning
