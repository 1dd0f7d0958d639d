#include "experiments/missions/tag_follow_flight.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/yaml_write_archive.h"
#include "control/constants.h"
#include "experiments/bench/sample_statistics.h"
#include "experiments/missions/odometry_adapter.h"
#include "experiments/missions/tag_mapping_flight.h"
#include "experiments/tags/drifting_ground_robot.h"
#include "experiments/tags/ground_mission_inset.h"
#include "experiments/tags/image_centre_offset.h"
#include "experiments/tags/tag_map_evaluation.h"
#include "experiments/tags/tagged_object_mover.h"
#include "experiments/tags/tags_mission_scene.h"
#include "experiments/tags/tags_scenario_field.h"
#include "output/csv_writer.h"
#include "output/svg_plot.h"
#include "perception/tags/tag_map_writer.h"
#include "planning/ground_mission/ground_mission_planner.h"
#include "planning/ground_mission/ground_mission_timeline.h"
#include "planning/tag_follow/tag_follow_autopilot.h"
#include "planning/tag_mapping/tag_mapping_params_io.h"
#include "sim/sim_params_io.h"

namespace aperture::experiments {
namespace {

// Issue 16's acceptance: the robot's tag within 10 % of the image width of the image centre.
constexpr double kFollowMaxOffsetOfWidth = 0.10;
// Simulated time after the robot's mission that `aperture sim` flies [s].
constexpr double kFollowDurationMarginS = 2.0;
// What `aperture sim` allows for the follower to find the robot and lock on before the robot
// starts [s] (the SITL tests lock within ~5-8 s from the scenario's start pose).
constexpr double kLockAllowanceS = 12.0;
constexpr double kObjectsCsvRateHz = 10.0;
// Ground truth sampled for the offset: every 5th 1 kHz state (200 Hz).
constexpr int kOffsetDecimation = 5;
// A carried obstacle: in front of the robot, this far from the robot's front, lifted [m].
constexpr double kGripperGapM = 0.02;
constexpr double kCarryLiftM = 0.05;
// What `aperture sim` allows for the mission planned on the map beyond the one planned on the
// truth (the map's few centimetres can change the path) [fraction].
constexpr double kMapPlanAllowance = 0.5;
// Simulated time beyond the planned mapping flight (filter start, map solve) [s].
constexpr double kMappingMarginS = 5.0;
// Time allowed per drive segment for the relocalization stop (a fix takes one frame) [s].
constexpr double kFixAllowanceS = 0.5;

// The quadrotor's side of the mission: with a mapping stage (mission `deliver`) the mapping flight
// first, then, once it reports done (`on_mapped` plans the robot's mission on the map), the
// follower; without it, the follower from the start. Both stages take every IMU sample and
// odometry pose, so the follower's estimate is warm at the hand-over; frames and steps go to the
// stage that flies. Done `finished` says so.
class FollowStages final : public perception::Autopilot {
 public:
  FollowStages(planning::TagMappingAutopilot* mapping, planning::TagFollowAutopilot* follow,
               std::function<void(double)> on_mapped, std::function<bool(double)> finished)
      : mapping_(mapping),
        follow_(follow),
        on_mapped_(std::move(on_mapped)),
        finished_(std::move(finished)) {}

  std::string name() const override { return mapping_ ? "map_then_follow" : follow_->name(); }
  void OnImu(const perception::ImuSample& sample) override {
    if (mapping_) mapping_->OnImu(sample);
    follow_->OnImu(sample);
  }
  void OnOdometry(const perception::PoseMeasurement& pose_WB) {
    if (mapping_) mapping_->OnOdometry(pose_WB);
    follow_->OnOdometry(pose_WB);
  }
  void OnFrame(const perception::Frame& frame) override {
    if (mapping()) {
      mapping_->OnFrame(frame);
    } else {
      follow_->OnFrame(frame);
    }
  }
  perception::AutopilotCommand Step(double t_s) override {
    if (mapping()) {
      const perception::AutopilotCommand command = mapping_->Step(t_s);
      if (!command.done) return command;
      mapped_ = true;
      on_mapped_(t_s);
    }
    perception::AutopilotCommand command = follow_->Step(t_s);
    command.done = finished_(t_s);
    return command;
  }
  std::string status() const override {
    return mapping() ? "mapping: " + mapping_->status() : follow_->status();
  }
  void DrawOverlay(cv::Mat& bgr) const {
    if (mapping()) {
      mapping_->DrawOverlay(bgr);
    } else {
      follow_->DrawOverlay(bgr);
    }
  }
  bool mapping() const { return mapping_ && !mapped_; }

 private:
  planning::TagMappingAutopilot* mapping_;
  planning::TagFollowAutopilot* follow_;
  std::function<void(double)> on_mapped_;
  std::function<bool(double)> finished_;
  bool mapped_ = false;
};

class TagFollowFlight final : public MissionFlight {
 public:
  TagFollowFlight(const MissionContext& context, bool map_first)
      : scene_(context.scenario.scene()),
        field_(context.scenario.params().tags),
        seed_(context.scenario.params().seed),
        p_WB_start_(context.sitl.initial_state.p_WB) {
    mission_name_ = map_first ? "deliver" : "follow";
    const char* mission_name = mission_name_.c_str();
    const int camera_index = TagsDownCameraIndex(context.scenario, mission_name);
    odometry_ = LoadOdometryParams(context, 31);
    if (map_first) {
      mapping_params_ = TagsMappingParams(context, mission_name);
      context.params.ReadSection("map", &mapping_params_);
    }
    context.params.Read("robot_start_s", &robot_start_s_);
    context.params.Read("robot_speed_mps", &robot_speed_mps_);
    if (!(robot_start_s_ >= 0.0) || !std::isfinite(robot_start_s_)) {
      throw std::invalid_argument("mission.robot_start_s must be >= 0 [s]");
    }
    if (!(robot_speed_mps_ > 0.0) || !std::isfinite(robot_speed_mps_)) {
      throw std::invalid_argument("mission.robot_speed_mps must be > 0 [m/s]");
    }
    context.params.Read("robot_drift_scale_sigma", &drift_.scale_sigma);
    context.params.Read("robot_drift_heading_sigma_rad", &drift_.heading_sigma_rad);
    context.params.Read("robot_relocalize", &relocalization_.enabled);
    context.params.Read("robot_fix_timeout_s", &relocalization_.fix_timeout_s);
    context.params.Read("robot_max_correction_m", &relocalization_.max_correction_m);
    context.params.Read("robot_max_segment_m", &relocalization_.max_segment_m);
    params_.camera_id = camera_index;
    static_cast<perception::ImuNoiseParams&>(params_.fusion.filter) = context.sitl.imu;
    planning::LoadParams(context.params, &params_);

    // The robot's mission planned on the field's true tag poses: the one executed by `follow`,
    // the duration estimate of `deliver` (which plans on its map after the mapping flight).
    ground_.driving_speed_mps = robot_speed_mps_;
    if (!PlanGroundMission(TagsScenarioTagPoses(context.scenario))) {
      throw std::invalid_argument(
          std::string("mission '") + mission_name +
          "': the ground robot has no mission to the goal on this field (seed " +
          std::to_string(seed_) + "): every order of removals is blocked; try another --seed");
    }
    truth_plan_s_ = timeline_->duration_s() +
                    kFixAllowanceS * static_cast<double>(ground_robot_->commands().size());

    const sim::Scene& scene = context.scenario.scene();
    robot_.emplace(scene, "robot", "tag2");
    for (int k = 0; k < field_.movable_obstacles; ++k) {
      movable_.emplace_back(scene, "movable" + std::to_string(k),
                            "tag" + std::to_string(3 + field_.fixed_obstacles + k));
    }
    tag_height_m_ = scene.object("tag2").T_WO.translation().z();
    const sim::ScenarioCamera& camera = context.scenario.cameras()[camera_index];
    camera_ = camera.model;
    T_BC_ = *camera.T_BC;
    autopilot_ = std::make_unique<planning::TagFollowAutopilot>(
        params_, field_.tag_size_m, field_.area_m / 2, camera_, T_BC_,
        context.sitl.dynamics.vehicle, TagsFieldFrontEndParams(field_));
    if (map_first) {
      mapping_ = MakeTagsMappingAutopilot(context, mapping_params_);
      timeline_.reset();
      ground_robot_.reset();
    }
    stages_ = std::make_unique<FollowStages>(
        mapping_.get(), autopilot_.get(), [this](double t_s) { OnMapped(t_s); },
        [this](double t_s) {
          return (robot_done_t_s_ && t_s >= *robot_done_t_s_ + kFollowDurationMarginS) ||
                 ground_robot_state() == GroundRobotState::kFailSafe;
        });
    adapter_ = MakeOdometryAdapter(stages_.get(), odometry_);
  }

  perception::Autopilot& autopilot() override { return *adapter_; }
  // The run ends earlier, when the robot is done (FollowStages).
  double MinimumDurationS() const override {
    const double mapping_s =
        mapping_ ? mapping_->PlannedDurationS(p_WB_start_) + kMappingMarginS : 0.0;
    const double plan_s = mapping_ ? (1 + kMapPlanAllowance) * truth_plan_s_ : truth_plan_s_;
    return std::max(robot_start_s_, mapping_s + kLockAllowanceS) + plan_s + kFollowDurationMarginS;
  }
  YAML::Node EffectiveParams() const override {
    YAML::Node node;
    node["odometry"] = config::DumpParams(odometry_);
    if (mapping_) node["map"] = config::DumpParams(mapping_params_);
    return node;
  }
  void DrawOverlay(cv::Mat& onboard_bgr) const override {
    stages_->DrawOverlay(onboard_bgr);
    if (timeline_ && !track_.empty()) {
      DrawGroundMissionInset(ground_scene_, *timeline_, track_.back().sample,
                             {field_.goal_size_m.head<2>(), field_.robot_size_m.head<2>(),
                              field_.movable_size_m.head<2>()},
                             &onboard_bgr);
    }
  }

  void MoveObjects(double t_s, sim::Scene* scene) override {
    if (!ground_robot_) return;  // mapping: the robot stands at its start
    // The robot waits for the quadrotor to lock on above it (over the communication link).
    if (!robot_go_t_s_ && t_s >= robot_start_s_ && autopilot_->locked_t_s()) {
      robot_go_t_s_ = t_s;
      ground_robot_->Start(t_s);
    }
    ground_robot_->Advance(t_s, LatestFix());
    if (!robot_done_t_s_ && ground_robot_->state() == GroundRobotState::kDone) {
      robot_done_t_s_ = t_s;
    }
    const planning::GroundRobotSample s = ground_robot_->Now();
    robot_->MoveTo(robot_->PoseAt(s.robot_p_W, s.robot_yaw_rad), scene);
    for (int k = 0; k < static_cast<int>(movable_.size()); ++k) {
      movable_[k].MoveTo(MovableAt(s, k), scene);
    }
    if (track_.empty() || t_s > track_.back().t_s) track_.push_back({t_s, s});
    if (!contact_) contact_ = GroundContact(t_s, s);
  }

  MissionEvaluation Evaluate(const sim::SitlResult& result) override {
    sim_time_s_ = result.sim_time_s;
    MissionEvaluation out;
    nlohmann::json& f = out.figures;
    if (mapping_) AddMapFigures(&f);
    if (!ground_robot_) {
      f["collision"] = result.collision.has_value();
      f["robot_state"] = "no_mission";
      const std::string why = mapped_t_s_ ? "no robot mission on the map: " + plan_failure_
                                          : std::string("the mapping flight did not finish");
      f["plan_failure"] = why;
      out.outcome = mission_name_ + ": FAILED; " + why;
      return out;
    }
    const double go_t_s = robot_go_t_s_.value_or(control::kInf);
    const double execution_end_s = robot_done_t_s_.value_or(result.sim_time_s);
    std::vector<double> offsets;
    int outside_image = 0;
    for (std::size_t i = 0; i < result.trajectory.size(); i += kOffsetDecimation) {
      const control::QuadState& x = result.trajectory[i];
      if (x.t_s < go_t_s || x.t_s > execution_end_s) continue;
      const Eigen::Vector2d p_W = RobotPositionAt(x.t_s);
      const std::optional<double> offset =
          ImageCentreOffset(x, T_BC_, *camera_, Eigen::Vector3d(p_W.x(), p_W.y(), tag_height_m_));
      if (!offset) {
        ++outside_image;
        continue;
      }
      offsets.push_back(*offset);
      offset_t_s_.push_back(x.t_s);
    }
    offsets_ = offsets;
    const double max_offset = outside_image > 0 || offsets.empty()
                                  ? control::kInf
                                  : *std::max_element(offsets.begin(), offsets.end());
    const int within = static_cast<int>(std::count_if(
        offsets.begin(), offsets.end(), [](double o) { return o <= kFollowMaxOffsetOfWidth; }));
    const std::optional<double> found_t_s = autopilot_->first_seen_t_s();
    const bool executed = robot_done_t_s_.has_value();
    const planning::GroundRobotSample end = ground_robot_->Now();
    // The first-aid kit, put down at the gripper's reach in front of the robot (D.6).
    const Eigen::Vector2d kit_p_W =
        end.robot_p_W + ground_.grasp_radius_m * Eigen::Vector2d(std::cos(end.robot_yaw_rad),
                                                                 std::sin(end.robot_yaw_rad));
    const bool kit_on_goal = executed && planning::DistanceToBox(GoalBox(), kit_p_W) == 0.0;

    out.passed =
        !result.collision && !contact_ && kit_on_goal && max_offset <= kFollowMaxOffsetOfWidth;
    f["max_offset_of_width"] = FiniteOrNull(max_offset);
    if (!offsets.empty() && outside_image == 0) {
      f["max_offset_t_s"] =
          offset_t_s_[std::max_element(offsets.begin(), offsets.end()) - offsets.begin()];
    }
    f["median_offset_of_width"] =
        FiniteOrNull(offsets.empty() ? control::kNaN : UpperMedian(offsets));
    f["offset_target_of_width"] = kFollowMaxOffsetOfWidth;
    f["samples_within_target"] = within;
    f["samples_outside_image"] = outside_image;
    f["samples"] = static_cast<int>(offsets.size()) + outside_image;
    f["robot_found_t_s"] = found_t_s ? nlohmann::json(*found_t_s) : nlohmann::json();
    f["robot_locked_t_s"] = FiniteOrNull(autopilot_->locked_t_s().value_or(control::kNaN));
    f["robot_start_t_s"] = FiniteOrNull(robot_go_t_s_.value_or(control::kNaN));
    f["robot_speed_mps"] = robot_speed_mps_;
    f["robot_mission_s"] = timeline_->duration_s();
    f["robot_mission_executed"] = executed;
    f["robot_state"] = ToString(ground_robot_->state());
    f["robot_fail_safe_reason"] = ground_robot_->fail_reason();
    f["robot_contact"] = contact_ ? nlohmann::json(contact_->what) : nlohmann::json();
    f["robot_contact_t_s"] = contact_ ? nlohmann::json(contact_->t_s) : nlohmann::json();
    f["kit_on_goal"] = kit_on_goal;
    f["kit_from_goal_m"] = (kit_p_W - ground_scene_.goal_p_W).norm();
    const std::vector<GroundRelocalization>& fixes = ground_robot_->relocalizations();
    f["relocalizations"] = static_cast<int>(fixes.size());
    double max_correction_m = 0.0, max_fix_error_m = 0.0;
    for (const GroundRelocalization& fix : fixes) {
      max_correction_m = std::max(max_correction_m, fix.correction_m);
      max_fix_error_m = std::max(max_fix_error_m, fix.fix_error_m);
    }
    f["relocalization_max_correction_m"] = max_correction_m;
    f["relocalization_max_fix_error_m"] = max_fix_error_m;
    f["robot_removals"] = mission_.Order();
    f["robot_path_length_m"] = mission_.path_length_m();
    f["collision"] = result.collision.has_value();
    int frames_with_target = 0;
    for (const planning::TagFollowSample& s : autopilot_->trace()) {
      frames_with_target += s.target_seen ? 1 : 0;
    }
    f["frames"] = static_cast<int>(autopilot_->trace().size());
    f["frames_with_target"] = frames_with_target;
    const std::string robot_outcome =
        contact_ ? "COLLIDED (" + contact_->what + ")"
        : ground_robot_->state() == GroundRobotState::kFailSafe
            ? "stopped fail-safe (" + ground_robot_->fail_reason() + ")"
        : !executed   ? std::string("NOT finished (raise --duration)")
        : kit_on_goal ? std::string("executed, kit on the goal")
                      : std::string("executed, kit OFF the goal");
    char line[512];
    std::snprintf(line, sizeof(line),
                  "%s: %s; robot found at %.1f s, its %.0f s mission (%zu removals, %zu "
                  "relocalizations) %s; tag centre at most %.1f %% of the image width from the "
                  "centre (target %.0f %%), median %.1f %%",
                  mission_name_.c_str(), out.passed ? "passed" : "FAILED",
                  found_t_s.value_or(control::kNaN), timeline_->duration_s(),
                  mission_.removals.size(), fixes.size(), robot_outcome.c_str(), 100 * max_offset,
                  100 * kFollowMaxOffsetOfWidth,
                  offsets.empty() ? control::kNaN : 100 * UpperMedian(offsets));
    out.outcome = line;
    return out;
  }

  std::map<std::string, std::string> WriteFiles(const std::string& directory) const override {
    const std::filesystem::path dir(directory);
    output::CsvWriter objects((dir / "objects.csv").string(),
                              {"t", "name", "tx", "ty", "tz", "qx", "qy", "qz", "qw"});
    double next_t_s = 0.0;
    for (const TrackPoint& point : track_) {
      if (point.t_s < next_t_s) continue;
      next_t_s = (std::floor(point.t_s * kObjectsCsvRateHz) + 1) / kObjectsCsvRateHz;
      const double t_s = point.t_s;
      const planning::GroundRobotSample& s = point.sample;
      const auto write = [&](const std::string& name, const Eigen::Isometry3d& T_WO) {
        const Eigen::Quaterniond q(T_WO.linear());
        const Eigen::Vector3d& p = T_WO.translation();
        objects.WriteCells({t_s, name, p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()});
      };
      write("robot", robot_->PoseAt(s.robot_p_W, s.robot_yaw_rad));
      for (int k = 0; k < static_cast<int>(movable_.size()); ++k) {
        write("movable" + std::to_string(k), MovableAt(s, k));
      }
    }
    objects.Close();
    output::CsvWriter follow((dir / "follow.csv").string(),
                             {"t", "target_seen", "u_px", "v_px", "servo_error", "vx_B", "vy_B",
                              "vz_B", "yaw_rate_radps"});
    for (const planning::TagFollowSample& s : autopilot_->trace()) {
      follow.WriteRow({s.t_s, s.target_seen ? 1.0 : 0.0, s.target_center_px.x(),
                       s.target_center_px.y(), s.servo_error, s.v_B.x(), s.v_B.y(), s.v_B.z(),
                       s.yaw_rate_radps});
    }
    follow.Close();
    std::map<std::string, std::string> files = {{"objects", "objects.csv"},
                                                {"follow", "follow.csv"}};
    if (mapped_t_s_) {
      const std::vector<perception::MappedTag> tags = mapping_->map().Tags();
      perception::WriteTagMapYaml((dir / "tag_map.yaml").string(), tags, mapping_->map().params());
      perception::WriteTagMapTopView((dir / "tag_map.png").string(), tags);
      files["tag_map"] = "tag_map.yaml";
      files["tag_map_top_view"] = "tag_map.png";
    }
    return files;
  }

  void AddReportSections(const MissionEvaluation& /*evaluation*/, const sim::SitlResult& /*result*/,
                         output::HtmlReport* report) const override {
    if (timeline_) AddPlanPlot(report);
    if (offsets_.empty()) return;
    report->AddSection("Tag servo over the driving robot");
    std::vector<double> percent, target;
    for (double o : offsets_) percent.push_back(100 * o);
    target.assign(offsets_.size(), 100 * kFollowMaxOffsetOfWidth);
    output::SvgPlot plot({"Robot tag from the image centre (ground truth)", "t [s]",
                          "offset [% of the image width]"});
    plot.AddLine("tag centre", offset_t_s_, percent).AddLine("bound", offset_t_s_, target);
    report->AddSvg(plot.Render(), "While the robot executes its mission");
  }

 private:
  // Plans the robot's mission on the tag poses T_WT_by_id (the truth or the map) and readies its
  // execution; false (and plan_failure_ says why) when there is none.
  bool PlanGroundMission(const std::map<int, Eigen::Isometry3d>& T_WT_by_id) {
    try {
      ground_scene_ = TagsMissionScene(field_, T_WT_by_id);
      mission_ = planning::GroundMissionPlanner(ground_scene_, ground_).Plan();
    } catch (const std::invalid_argument& e) {
      plan_failure_ = e.what();
      return false;
    }
    if (!mission_.solved()) {
      plan_failure_ = "no order of removals reaches the goal";
      return false;
    }
    timeline_.emplace(mission_, ground_scene_, ground_);
    ground_robot_.emplace(*timeline_, drift_, relocalization_, seed_);
    return true;
  }

  // The mapping flight is over: the map optimized, the robot's mission planned on it.
  void OnMapped(double t_s) {
    mapped_t_s_ = t_s;
    map_solve_ = mapping_->map().Optimize();
    map_evaluation_ = EvaluateTagMap(mapping_->map(), scene_);  // before anything moves
    std::map<int, Eigen::Isometry3d> T_WT_by_id;
    for (const perception::MappedTag& tag : mapping_->map().Tags()) T_WT_by_id[tag.id] = tag.T_WT;
    PlanGroundMission(T_WT_by_id);
  }

  // The field from above: the obstacles as planned on (truth or map), the planned robot path
  // and the path the robot truly drove.
  void AddPlanPlot(output::HtmlReport* report) const {
    report->AddSection("The robot's mission: plan and execution");
    output::SvgPlot plot({"Field from above", "x [m]", "y [m]"});
    const auto outline = [&](const std::string& name, const planning::GroundBox& box) {
      std::vector<double> xs, ys;
      const Eigen::Rotation2Dd R(box.yaw_rad);
      for (const Eigen::Vector2d& c :
           {Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(0.5, -0.5), Eigen::Vector2d(0.5, 0.5),
            Eigen::Vector2d(-0.5, 0.5), Eigen::Vector2d(-0.5, -0.5)}) {
        const Eigen::Vector2d p = box.p_W + R * box.size_m.cwiseProduct(c);
        xs.push_back(p.x());
        ys.push_back(p.y());
      }
      plot.AddLine(name, xs, ys);
    };
    for (size_t k = 0; k < ground_scene_.fixed_obstacles.size(); ++k) {
      outline("fixed " + std::to_string(k), ground_scene_.fixed_obstacles[k]);
    }
    for (size_t k = 0; k < ground_scene_.movable_obstacles.size(); ++k) {
      outline("movable " + std::to_string(k), ground_scene_.movable_obstacles[k]);
    }
    outline("goal", GoalBox());
    std::vector<double> plan_x, plan_y, true_x, true_y;
    for (double t_s = 0.0; t_s <= timeline_->duration_s(); t_s += 0.25) {
      const Eigen::Vector2d p = timeline_->Sample(t_s).robot_p_W;
      plan_x.push_back(p.x());
      plan_y.push_back(p.y());
    }
    for (const TrackPoint& point : track_) {
      true_x.push_back(point.sample.robot_p_W.x());
      true_y.push_back(point.sample.robot_p_W.y());
    }
    plot.AddLine("planned robot path", plan_x, plan_y).AddLine("driven (truth)", true_x, true_y);
    report->AddSvg(plot.Render(), mapping_ ? "Obstacles and goal as mapped; removals: " +
                                                 std::to_string(mission_.removals.size())
                                           : "Obstacles and goal as the scenario has them");
  }

  // The map of mission `deliver` scored on the scene (as mission `map` scores it).
  void AddMapFigures(nlohmann::json* figures) const {
    nlohmann::json& f = *figures;
    f["mapped_t_s"] = FiniteOrNull(mapped_t_s_.value_or(control::kNaN));
    if (!map_evaluation_) return;
    const TagMapEvaluation& map = *map_evaluation_;
    f["map_rms_after_m"] = map.rms_after_m;
    f["map_rms_before_m"] = map.rms_before_m;
    f["map_tags_mapped"] = static_cast<int>(map.tags.size());
    f["map_flipped_tags"] = map.flipped;
    f["map_solve_converged"] = map_solve_ && map_solve_->converged;
  }

  GroundRobotState ground_robot_state() const {
    return ground_robot_ ? ground_robot_->state() : GroundRobotState::kWaitingToStart;
  }

  struct TrackPoint {
    double t_s = 0.0;
    planning::GroundRobotSample sample;
  };
  struct Contact {
    double t_s = 0.0;
    std::string what;
  };

  // The robot's true position at t_s, linear between the rendered frames' samples.
  Eigen::Vector2d RobotPositionAt(double t_s) const {
    const auto after =
        std::upper_bound(track_.begin(), track_.end(), t_s,
                         [](double t, const TrackPoint& point) { return t < point.t_s; });
    if (after == track_.begin()) return track_.front().sample.robot_p_W;
    if (after == track_.end()) return track_.back().sample.robot_p_W;
    const TrackPoint& a = *(after - 1);
    const double f = (t_s - a.t_s) / (after->t_s - a.t_s);
    return a.sample.robot_p_W + f * (after->sample.robot_p_W - a.sample.robot_p_W);
  }

  // The aerial robot's latest estimate of the robot's tag pose (planning::TagFollowSample::T_WT).
  std::optional<GroundRobotFix> LatestFix() {
    const std::vector<planning::TagFollowSample>& trace = autopilot_->trace();
    for (; fix_cursor_ < trace.size(); ++fix_cursor_) {
      const planning::TagFollowSample& sample = trace[fix_cursor_];
      if (!sample.T_WT) continue;
      latest_fix_ = GroundRobotFix{sample.t_s, sample.T_WT->translation().head<2>(),
                                   TagGroundYaw(*sample.T_WT)};
    }
    return latest_fix_;
  }

  // The goal's mat, where the kit is to be put.
  planning::GroundBox GoalBox() const {
    return {ground_scene_.goal_p_W, field_.goal_size_m.head<2>(), 0.0};
  }

  // The first overlap of the robot's base (or of the obstacle it carries) with an obstacle, the
  // victim's footprint or the field's border (ground truth).
  std::optional<Contact> GroundContact(double t_s, const planning::GroundRobotSample& s) const {
    const planning::GroundBox base{s.robot_p_W, field_.robot_size_m.head<2>(), s.robot_yaw_rad};
    std::vector<std::pair<std::string, planning::GroundBox>> bodies = {{"robot", base}};
    if (s.carried >= 0 && s.activity != "grasp" && s.activity != "place") {
      const Eigen::Isometry3d T_WO = MovableAt(s, s.carried);
      bodies.push_back(
          {"carried obstacle",
           {T_WO.translation().head<2>(), field_.movable_size_m.head<2>(), s.robot_yaw_rad}});
    }
    std::vector<std::pair<std::string, planning::GroundBox>> obstacles;
    for (size_t k = 0; k < ground_scene_.fixed_obstacles.size(); ++k) {
      obstacles.push_back(
          {"fixed obstacle " + std::to_string(k), ground_scene_.fixed_obstacles[k]});
    }
    for (size_t k = 0; k < s.movable_p_W.size(); ++k) {
      if (static_cast<int>(k) == s.carried) continue;
      obstacles.push_back(
          {"movable obstacle " + std::to_string(k),
           {s.movable_p_W[k], field_.movable_size_m.head<2>(), s.movable_yaw_rad[k]}});
    }
    const Eigen::Rotation2Dd R_WR(s.robot_yaw_rad);
    for (const double sx : {-0.5, 0.5}) {
      for (const double sy : {-0.5, 0.5}) {
        const Eigen::Vector2d corner_W =
            s.robot_p_W +
            R_WR * field_.robot_size_m.head<2>().cwiseProduct(Eigen::Vector2d(sx, sy));
        if ((corner_W.array() < ground_scene_.area_min_W.array()).any() ||
            (corner_W.array() > ground_scene_.area_max_W.array()).any()) {
          return Contact{t_s, "robot leaves the field"};
        }
      }
    }
    for (const auto& [body, box] : bodies) {
      // The victim: the planner's disc of goal_radius_m around the goal (the mat is flat).
      if (planning::DistanceToBox(box, ground_scene_.goal_p_W) < ground_scene_.goal_radius_m) {
        return Contact{t_s, body + " touches the victim on the goal"};
      }
      for (const auto& [name, obstacle] : obstacles) {
        if (planning::BoxesOverlap(box, obstacle)) {
          return Contact{t_s, body + " touches " + name};
        }
      }
    }
    return std::nullopt;
  }

  // Movable obstacle k: in the gripper in front of the robot while carried, else where the
  // timeline has it.
  Eigen::Isometry3d MovableAt(const planning::GroundRobotSample& s, int k) const {
    if (s.carried != k) return movable_[k].PoseAt(s.movable_p_W[k], s.movable_yaw_rad[k]);
    const Eigen::Vector2d heading(std::cos(s.robot_yaw_rad), std::sin(s.robot_yaw_rad));
    const double reach_m =
        0.5 * (field_.robot_size_m.x() + field_.movable_size_m.x()) + kGripperGapM;
    Eigen::Isometry3d T_WO = movable_[k].PoseAt(s.robot_p_W + reach_m * heading, s.robot_yaw_rad);
    T_WO.translation().z() += kCarryLiftM;
    return T_WO;
  }

  const sim::Scene& scene_;
  std::string mission_name_;
  sim::TagsSceneParams field_;
  std::uint64_t seed_;
  Eigen::Vector3d p_WB_start_;
  GroundOdometryDriftParams drift_;
  GroundRelocalizationParams relocalization_;
  planning::TagMappingParams mapping_params_;
  std::unique_ptr<planning::TagMappingAutopilot> mapping_;  // mission `deliver` only
  std::optional<double> mapped_t_s_;
  std::optional<perception::TagMapSolveSummary> map_solve_;
  std::optional<TagMapEvaluation> map_evaluation_;
  std::string plan_failure_;
  double truth_plan_s_ = 0.0;     // the execution of the mission planned on the truth [s]
  double robot_start_s_ = 0.0;    // earliest start; the robot also waits for the lock
  double robot_speed_mps_ = 0.3;  // the 0.3 m/s (D.7's planner default: 0.2)
  planning::TagFollowParams params_;
  sim::OdometrySensorParams odometry_;
  planning::GroundMissionParams ground_;
  planning::GroundMissionScene ground_scene_;
  planning::GroundMission mission_;
  std::optional<planning::GroundMissionTimeline> timeline_;
  std::optional<DriftingGroundRobot> ground_robot_;
  std::optional<TaggedObjectMover> robot_;
  std::vector<TaggedObjectMover> movable_;
  double tag_height_m_ = 0.0;
  std::shared_ptr<const perception::CameraModel> camera_;
  Eigen::Isometry3d T_BC_ = Eigen::Isometry3d::Identity();
  std::unique_ptr<planning::TagFollowAutopilot> autopilot_;
  std::unique_ptr<FollowStages> stages_;
  std::unique_ptr<OdometryAdapter> adapter_;
  double sim_time_s_ = 0.0;
  std::optional<double> robot_go_t_s_;    // when the robot started its mission
  std::optional<double> robot_done_t_s_;  // when it finished it
  std::vector<TrackPoint> track_;         // the truth at every rendered frame
  std::optional<Contact> contact_;
  size_t fix_cursor_ = 0;
  std::optional<GroundRobotFix> latest_fix_;
  std::vector<double> offsets_, offset_t_s_;
};

}  // namespace

std::unique_ptr<MissionFlight> MakeTagFollowFlight(const MissionContext& context) {
  return std::make_unique<TagFollowFlight>(context, false);
}

std::unique_ptr<MissionFlight> MakeTagDeliveryFlight(const MissionContext& context) {
  return std::make_unique<TagFollowFlight>(context, true);
}

}  // namespace aperture::experiments
