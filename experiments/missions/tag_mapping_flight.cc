#include "experiments/missions/tag_mapping_flight.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/yaml_write_archive.h"
#include "experiments/missions/odometry_adapter.h"
#include "experiments/tags/tag_map_evaluation.h"
#include "experiments/tags/tags_scenario_field.h"
#include "output/csv_writer.h"
#include "output/json_eigen.h"
#include "perception/tags/tag_map_writer.h"
#include "planning/tag_mapping/tag_mapping_params_io.h"
#include "sim/sim_params_io.h"

namespace aperture::experiments {
namespace {

// The acceptance: tag position RMS over the field [m].
constexpr double kMapRmsTargetM = 0.02;
// Simulated time beyond the planned flight that `aperture sim` gives the mission [s].
constexpr double kBeyondPlannedFlightS = 5.0;

class TagMappingFlight final : public MissionFlight {
 public:
  explicit TagMappingFlight(const MissionContext& context)
      : scene_(context.scenario.scene()),
        field_(context.scenario.params().tags),
        p_WB_start_(context.sitl.initial_state.p_WB) {
    odometry_ = LoadOdometryParams(context, 29);
    params_ = TagsMappingParams(context, "map");
    LoadParams(context.params, &params_);  // config::LoadParams: reads, rejects, validates
    autopilot_ = MakeTagsMappingAutopilot(context, params_);
    adapter_ = MakeOdometryAdapter(autopilot_.get(), odometry_);
  }

  perception::Autopilot& autopilot() override { return *adapter_; }
  // The planned flight from the start, and time for the filter to start and the map to solve.
  double MinimumDurationS() const override {
    return autopilot_->PlannedDurationS(p_WB_start_) + kBeyondPlannedFlightS;
  }
  YAML::Node EffectiveParams() const override {
    YAML::Node node = config::DumpParams(params_);
    node["odometry"] = config::DumpParams(odometry_);
    return node;
  }
  void DrawOverlay(cv::Mat& onboard_bgr) const override { autopilot_->DrawOverlay(onboard_bgr); }

  MissionEvaluation Evaluate(const sim::SitlResult& result) override {
    planning::TagMappingAutopilot& a = *autopilot_;
    const perception::TagMapSolveSummary solve = a.map().Optimize();
    evaluation_ = EvaluateTagMap(a.map(), scene_);
    const TagMapEvaluation& e = *evaluation_;
    const int tags_total = 3 + field_.fixed_obstacles + field_.movable_obstacles;
    const int tags_mapped = static_cast<int>(e.tags.size());
    const bool map_ok =
        tags_mapped == tags_total && e.rms_after_m <= kMapRmsTargetM && e.flipped == 0;
    MissionEvaluation out;
    out.passed = !result.collision && a.done() && map_ok;
    const double flight_time_s =
        a.flight_start_t_s()
            ? std::min(*a.flight_end_t_s(), result.sim_time_s) - *a.flight_start_t_s()
            : 0.0;
    nlohmann::json& f = out.figures;
    f["map_rms_after_m"] = e.rms_after_m;
    f["map_rms_before_m"] = e.rms_before_m;
    f["map_rms_target_m"] = kMapRmsTargetM;
    f["tags_mapped"] = tags_mapped;
    f["tags_total"] = tags_total;
    f["flipped_tags"] = e.flipped;
    f["flight_finished"] = a.done();
    f["collision"] = result.collision.has_value();
    f["flight_time_s"] = flight_time_s;
    f["map_mean_error_m"] = output::EigenToJson(e.mean_error_m);
    f["height_m"] = a.height_m();
    f["tracks"] = a.plan().tracks;
    f["track_spacing_m"] = a.plan().track_spacing_m;
    f["footprint_half_across_m"] = a.plan().half_across_m;
    f["footprint_half_along_m"] = a.plan().half_along_m;
    f["frames"] = a.frames();
    f["frames_with_tags"] = a.frames_with_tags();
    f["images_in_graph"] = a.map().images_in_graph();
    f["images_not_connected"] = a.map().pending_images();
    f["odometry_edges"] = a.map().odometry_edges();
    f["rejected_observations"] = solve.rejected_observations;
    f["map_solve_converged"] = solve.converged;
    f["map_solve_time_s"] = solve.solve_time_s;
    f["map_tags"] = e.PerTagJson();
    char line[240];
    std::snprintf(line, sizeof(line),
                  "tag map: %s, %d/%d tags, position RMS %.2f cm after optimization (%.2f cm "
                  "before; target %.0f cm), %d flipped, %.1f s of mapping flight%s",
                  out.passed ? "passed" : "FAILED", tags_mapped, tags_total, 100 * e.rms_after_m,
                  100 * e.rms_before_m, 100 * kMapRmsTargetM, e.flipped, flight_time_s,
                  a.done() ? "" : " (not finished: raise --duration)");
    out.outcome = line;
    return out;
  }

  std::map<std::string, std::string> WriteFiles(const std::string& directory) const override {
    if (!evaluation_) return {};
    const std::filesystem::path dir(directory);
    const std::vector<perception::MappedTag> tags = autopilot_->map().Tags();
    perception::WriteTagMapYaml((dir / "tag_map.yaml").string(), tags, autopilot_->map().params());
    perception::WriteTagMapTopView((dir / "tag_map.png").string(), tags);
    output::CsvWriter csv((dir / "tag_map_errors.csv").string(),
                          {"family", "id", "size_m", "true_x_m", "true_y_m", "true_z_m",
                           "error_x_m", "error_y_m", "error_z_m", "error_m", "error_before_m",
                           "rotation_error_deg", "flipped", "sigma_m", "observations", "rejected"});
    for (const TagMapError& t : evaluation_->tags) {
      csv.WriteCells({t.family, double(t.id), t.size_m, t.p_true_m.x(), t.p_true_m.y(),
                      t.p_true_m.z(), t.error_m.x(), t.error_m.y(), t.error_m.z(), t.error_m.norm(),
                      t.error_before_m.norm(), t.rotation_error_deg, double(t.flipped), t.sigma_m,
                      double(t.observations), double(t.rejected)});
    }
    csv.Close();
    return {{"tag_map", "tag_map.yaml"},
            {"tag_map_top_view", "tag_map.png"},
            {"tag_map_errors", "tag_map_errors.csv"}};
  }

  void AddReportSections(const MissionEvaluation& evaluation, const sim::SitlResult& /*result*/,
                         output::HtmlReport* report) const override {
    if (!evaluation_) return;
    report->AddSection("Tag map");
    report->AddParagraph(evaluation.outcome +
                         ". Errors in the origin tag's frame against the scene's ground truth; "
                         "the map comes from the downward camera's images with the onboard "
                         "estimate's gravity and camera pose per image.");
    report->AddImage(perception::DrawTagMapTopView(autopilot_->map().Tags()),
                     "The map from above: tag outlines, x_T in red, 3-sigma ellipses, grey "
                     "crosses before optimization");
    report->AddTable(evaluation.figures["map_tags"], "Per mapped tag");
  }

 private:
  const sim::Scene& scene_;
  sim::TagsSceneParams field_;
  Eigen::Vector3d p_WB_start_;
  planning::TagMappingParams params_;
  sim::OdometrySensorParams odometry_;
  std::unique_ptr<planning::TagMappingAutopilot> autopilot_;
  std::unique_ptr<OdometryAdapter> adapter_;
  std::optional<TagMapEvaluation> evaluation_;  // of Evaluate
};

}  // namespace

planning::TagMappingParams TagsMappingParams(const MissionContext& context,
                                             const std::string& mission) {
  planning::TagMappingParams params;
  params.camera_id = TagsDownCameraIndex(context.scenario, mission);
  static_cast<perception::ImuNoiseParams&>(params.fusion.filter) = context.sitl.imu;
  return params;
}

std::unique_ptr<planning::TagMappingAutopilot> MakeTagsMappingAutopilot(
    const MissionContext& context, const planning::TagMappingParams& params) {
  const sim::TagsSceneParams& field = context.scenario.params().tags;
  const sim::ScenarioCamera& camera = context.scenario.cameras()[params.camera_id];
  return std::make_unique<planning::TagMappingAutopilot>(
      params, TagsFieldForMapping(field), camera.model, *camera.T_BC, context.sitl.dynamics.vehicle,
      TagsFieldFrontEndParams(field), perception::TagMapParams{});
}

std::unique_ptr<MissionFlight> MakeTagMappingFlight(const MissionContext& context) {
  return std::make_unique<TagMappingFlight>(context);
}

}  // namespace aperture::experiments
