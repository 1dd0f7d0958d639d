#include "experiments/tags/tag_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "control/so3.h"
#include "experiments/bench/sample_statistics.h"
#include "experiments/bench/section_record.h"
#include "experiments/tags/missions_bench_section.h"
#include "experiments/tags/tag_map_evaluation.h"
#include "experiments/tags/tags_scenario_field.h"
#include "output/csv_writer.h"
#include "output/svg_plot.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/tags/tag_front_end.h"
#include "perception/tags/tag_map.h"
#include "sim/render/camera_effects.h"
#include "sim/scenario/scenario.h"
#include "sim/scene/apriltag_object.h"

namespace aperture::experiments {
namespace {

using perception::TagPoseCandidate;

constexpr double kDetectionTagSize_m = 0.16;
const char* const kFamilies[] = {"tag36h11", "tag16h5", "tag25h9", "tagStandard41h12"};
const std::vector<std::string> kTagFramesCsvColumns{
    "detector", "family",   "distance_m",          "angle_deg",
    "blur",     "detected", "translation_error_m", "rotation_error_deg",
    "ms"};
const std::vector<std::string> kObservationsCsvColumns{"frame",
                                                       "id",
                                                       "size_m",
                                                       "true_x_m",
                                                       "true_y_m",
                                                       "true_z_m",
                                                       "x_m",
                                                       "y_m",
                                                       "z_m",
                                                       "sigma_x_m",
                                                       "sigma_y_m",
                                                       "sigma_z_m",
                                                       "rotation_error_deg",
                                                       "view_angle_deg",
                                                       "corner_outward_px",
                                                       "best_rms_px",
                                                       "alternative_rms_px",
                                                       "lowest_error_rotation_error_deg"};

double Percentile90(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(0.9 * (values.size() - 1))];
}

const TagPoseCandidate& Nearest(const perception::TagPose& pose, const Eigen::Isometry3d& T_CT) {
  if (pose.alternative &&
      RotationErrorDeg(pose.alternative->T_CT, T_CT) < RotationErrorDeg(pose.best.T_CT, T_CT)) {
    return *pose.alternative;
  }
  return pose.best;
}

// ---- detection ----------------------------------------------------------------------------------

struct DetectionFrame {
  std::string family;
  int id;
  double distance_m, angle_deg;
  bool blur;
  Eigen::Isometry3d T_CT;
  cv::Mat image;
};

// One tag (on a white sheet twice its size) seen at distance and view angle, the camera aimed at
// a random point up to 0.3 of the half field of view off the tag.
DetectionFrame RenderDetectionFrame(const std::string& family, int id, std::mt19937* rng,
                                    const perception::CameraModel& camera, sim::RayCaster* caster) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  DetectionFrame frame;
  frame.family = family;
  frame.id = id;
  frame.distance_m = 0.5 + 5.5 * uniform(*rng);
  frame.angle_deg = 70.0 * uniform(*rng);
  frame.blur = uniform(*rng) < 1.0 / 3.0;
  sim::Scene scene;
  scene.lighting.ambient = 0.8f;
  scene.lighting.directional = 0.2f;
  const double pattern_m = sim::AprilTagPatternSize(family, kDetectionTagSize_m);
  sim::Material paper;
  paper.color = sim::Rgb::Constant(0.9f);
  Eigen::Isometry3d T_W_paper = Eigen::Isometry3d::Identity();
  T_W_paper.translation().z() = 0.001;  // behind the tag (z_O points into it)
  scene.AddObject({"paper", sim::Rectangle{Eigen::Vector2d::Constant(2.0 * pattern_m), {}, {}},
                   paper, T_W_paper});
  scene.AddObject(
      sim::MakeAprilTagObject(family, id, kDetectionTagSize_m, Eigen::Isometry3d::Identity()));
  // Camera on the tag's front side (-z_O), `angle` off the normal, looking at the aim point.
  const double azimuth = 2.0 * M_PI * uniform(*rng);
  const double angle = frame.angle_deg * M_PI / 180.0;
  const Eigen::Vector3d p_WC =
      frame.distance_m * Eigen::Vector3d(std::sin(angle) * std::cos(azimuth),
                                         std::sin(angle) * std::sin(azimuth), -std::cos(angle));
  const double off = 0.3 * frame.distance_m * std::tan(M_PI / 4.0);
  const Eigen::Vector3d aim(off * (2 * uniform(*rng) - 1), off * (2 * uniform(*rng) - 1), 0.0);
  const Eigen::Vector3d z_C = (aim - p_WC).normalized();
  Eigen::Vector3d x_C = z_C.cross(Eigen::Vector3d::UnitZ());
  if (x_C.norm() < 1e-6) x_C = Eigen::Vector3d::UnitX();
  x_C.normalize();
  const double roll = 2.0 * M_PI * uniform(*rng);
  x_C = Eigen::AngleAxisd(roll, z_C) * x_C;
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  T_WC.linear() << x_C, z_C.cross(x_C), z_C;
  T_WC.translation() = p_WC;
  frame.T_CT = T_WC.inverse();  // the tag sits at W's origin
  sim::CameraEffectsParams effects;
  effects.read_noise_sigma = 0.004;
  effects.full_well_electrons = 5000;
  effects.seed = (*rng)();
  if (frame.blur) {
    effects.exposure_s = 0.01;
    effects.motion_blur_subframes = 5;
  }
  const auto T_WC_at = [&](double t_s) {
    Eigen::Isometry3d T = T_WC;
    T.translation() += T_WC.linear() * Eigen::Vector3d(1.0 * t_s, 0.0, 0.0);  // 1 m/s along x_C
    return T;
  };
  frame.image =
      sim::CameraEffects(effects).Capture(*caster, scene, camera, T_WC_at, 0.0, 0).frame.image;
  return frame;
}

// frames.csv rows (kTagFramesCsvColumns) into *frames_csv_rows.
void RunDetection(const TagBenchOptions& options, nlohmann::json* summary,
                  output::HtmlReport* report, nlohmann::json* frames_csv_rows) {
  const perception::PinholeCamera camera(640, 480, {320.0, 320.0, 319.5, 239.5});
  std::mt19937 rng(static_cast<std::uint32_t>(options.seed));
  sim::RayCaster caster;
  const int frames_per_family = options.quick ? 6 : 60;
  std::vector<DetectionFrame> frames;
  for (const char* family : kFamilies) {
    for (int k = 0; k < frames_per_family; ++k) {
      frames.push_back(RenderDetectionFrame(family, k % 20, &rng, camera, &caster));
    }
  }
  nlohmann::json section = nlohmann::json::object();
  std::vector<output::NamedValues> time_groups;
  for (const std::string& name : options.detectors.Names()) {
    for (const char* family : kFamilies) {
      perception::TagDetectorParams params;
      params.families = {family};
      std::unique_ptr<perception::TagDetector> detector;
      try {
        detector = options.detectors.Create(name, params);
      } catch (const std::invalid_argument& error) {
        section[name][family] = {{"supported", false}, {"reason", error.what()}};
        continue;
      }
      std::vector<double> translation_errors, rotation_errors, times_ms;
      int detected = 0, total = 0, false_detections = 0;
      std::map<std::string, std::pair<int, int>> by_distance;  // bin -> (detected, total)
      for (const DetectionFrame& frame : frames) {
        if (frame.family != family) continue;
        ++total;
        const auto start = std::chrono::steady_clock::now();
        std::optional<perception::TagPose> pose;
        for (const perception::TagDetection& detection : detector->Detect(frame.image)) {
          if (detection.id != frame.id) {  // one tag in view: any other id is false
            ++false_detections;
            continue;
          }
          pose = perception::EstimateTagPose(camera, detection.corners_px, kDetectionTagSize_m);
        }
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        times_ms.push_back(ms);
        const std::string bin = frame.distance_m < 2   ? "0.5-2m"
                                : frame.distance_m < 4 ? "2-4m"
                                                       : "4-6m";
        ++by_distance[bin].second;
        double t_error = std::nan(""), r_error = std::nan("");
        if (pose) {
          ++detected;
          ++by_distance[bin].first;
          const TagPoseCandidate& nearest = Nearest(*pose, frame.T_CT);
          t_error = (nearest.T_CT.translation() - frame.T_CT.translation()).norm();
          r_error = RotationErrorDeg(nearest.T_CT, frame.T_CT);
          translation_errors.push_back(t_error);
          rotation_errors.push_back(r_error);
        }
        frames_csv_rows->push_back({name, std::string(family), frame.distance_m, frame.angle_deg,
                                    double(frame.blur), double(pose.has_value()), t_error, r_error,
                                    ms});
      }
      nlohmann::json rates = nlohmann::json::object();
      for (const auto& [bin, counts] : by_distance) {
        rates[bin] = counts.second ? double(counts.first) / counts.second : 0.0;
      }
      section[name][family] = {
          {"supported", true},
          {"frames", total},
          {"detection_rate", total ? double(detected) / total : 0.0},
          {"false_detections", false_detections},
          {"detection_rate_by_distance", rates},
          {"median_translation_error_m", UpperMedian(translation_errors)},
          {"p90_translation_error_m", Percentile90(translation_errors)},
          {"median_rotation_error_deg", UpperMedian(rotation_errors)},
          {"median_ms", UpperMedian(times_ms)},
      };
      time_groups.push_back({name + " " + family, times_ms});
    }
  }
  (*summary)["detection"] = section;
  report->AddSection("Detection per detector and family");
  report->AddParagraph("Single " + std::to_string(kDetectionTagSize_m) +
                       " m tags at 0.5-6 m, 0-70 deg, a third with motion blur; 640x480, f = "
                       "320 px. Errors of the candidate nearer the truth.");
  report->AddTable(section);
  report->AddSvg(output::SvgPlot::BoxPlot({"Detection + pose time", "", "ms"}, time_groups));
}

// ---- mapping ------------------------------------------------------------------------------------

// The mapping section; one observations.csv row (kObservationsCsvColumns) per tag observation
// into *observation_rows.
void RunMapping(const TagBenchOptions& options, nlohmann::json* summary, output::HtmlReport* report,
                nlohmann::json* observation_rows) {
  sim::Scenario scenario = sim::BuildScenario(sim::LoadScenarioParams(
      sim::ScenarioConfig("tags", {}, {"seed=" + std::to_string(options.seed)})));
  const sim::TagsSceneParams& field = scenario.params().tags;
  const sim::ScenarioCamera& camera = scenario.camera("down");
  const perception::TagFrontEndParams params = TagsFieldFrontEndParams(field);
  perception::TagFrontEnd front_end(options.detectors.Create("apriltag", params.detection),
                                    camera.model, params);
  perception::TagFlipResolverParams disabled;
  disabled.enabled = false;
  perception::TagFlipResolver lowest_error(disabled);
  perception::TagMap resolved_map, unresolved_map, without_odometry_map;
  const perception::TagMapParams& map_params = resolved_map.params();
  const int frames_per_lane = options.quick ? 20 : 40;
  // 2.5 m (the scenario's start height): the 90 deg camera sees 5 x 3.75 m, so the first lane,
  // over the origin tag, also sees the tags up to ~2.3 m beside and ~3.4 m ahead of it (the map
  // grows only from images that see a mapped tag).
  const double height_m = 2.5;
  const double lanes_x_m[] = {0.0, 4.0 / 3.0, 8.0 / 3.0, 4.0};
  sim::RayCaster caster;
  std::mt19937 rng(options.seed);
  std::normal_distribution<double> normal;
  const auto gaussian = [&] { return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)); };
  std::optional<Eigen::Isometry3d> T_WC_previous, T_OC;
  int flips_resolved = 0, flips_unresolved = 0, posed = 0, frame_index = 0;
  std::vector<double> t_axis, detections_per_frame, corner_errors_px;
  for (int lane = 0; lane < 4; ++lane) {
    for (int k = 0; k < frames_per_lane; ++k, ++frame_index) {
      const double along = -0.5 + 7.0 * k / (frames_per_lane - 1);
      const double y = lane % 2 ? field.area_m.y() - along : along;
      Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
      T_WB.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      T_WB.translation() = Eigen::Vector3d(lanes_x_m[lane], y, height_m);
      const Eigen::Isometry3d T_WC = camera.T_WC(T_WB);
      const double t_s = frame_index / camera.rate_hz;
      const cv::Mat image = camera.effects
                                .Capture(
                                    caster, scenario.scene(), *camera.model,
                                    [&](double) { return T_WC; }, t_s, frame_index, camera.render)
                                .frame.image;
      const perception::TagFrameResult result = front_end.Process(image, t_s);
      std::vector<perception::TagPoseInImage> posed_tags;
      std::vector<perception::TagMapObservation> resolved, unresolved;
      std::vector<Eigen::Isometry3d> truth;
      std::vector<std::vector<double>> rows;  // of observations.csv, completed below
      for (const perception::TagResult& tag : result.tags) {
        const int object = scenario.scene().FindId("tag" + std::to_string(tag.detection.id));
        if (!tag.pose || object < 0) continue;
        posed_tags.push_back({tag.detection.family, tag.detection.id, *tag.pose});
        truth.push_back(T_WC.inverse() * scenario.scene().object(object).T_WO);
        // Detected corners against the projected truth; `outward`: along the line from the
        // projected centre through the corner (> 0: the tag looks larger, i.e. nearer).
        Eigen::Vector2d centre_px;
        const bool centre_ok = camera.model->Project(truth.back().translation(), &centre_px);
        double outward_px = 0.0;
        int projected = 0;
        for (int c = 0; c < 4; ++c) {
          Eigen::Vector2d corner_px;
          if (camera.model->Project(truth.back() * perception::TagCorner(c, tag.size_m),
                                    &corner_px)) {
            const Eigen::Vector2d error_px = tag.detection.corners_px[c] - corner_px;
            corner_errors_px.push_back(error_px.norm());
            if (centre_ok) outward_px += error_px.dot((corner_px - centre_px).normalized());
            ++projected;
          }
        }
        resolved.push_back({tag.detection.family, tag.detection.id, tag.size_m, tag.chosen().T_CT,
                            tag.chosen().covariance});
        {
          const Eigen::Vector3d& p_true = truth.back().translation();
          const Eigen::Vector3d& p = tag.chosen().T_CT.translation();
          const Eigen::Vector3d sigma = tag.chosen().covariance.diagonal().head<3>().cwiseSqrt();
          // View angle: between the line of sight and the tag's normal (z_T).
          const double view_deg =
              std::acos(std::min(1.0, p_true.normalized().dot(truth.back().linear().col(2)))) *
              180.0 / M_PI;
          rows.push_back({double(frame_index), double(tag.detection.id), tag.size_m, p_true.x(),
                          p_true.y(), p_true.z(), p.x(), p.y(), p.z(), sigma.x(), sigma.y(),
                          sigma.z(), RotationErrorDeg(tag.chosen().T_CT, truth.back()), view_deg,
                          projected ? outward_px / projected : std::nan(""), tag.pose->best.rms_px,
                          tag.pose->alternative ? tag.pose->alternative->rms_px : std::nan("")});
        }
      }
      const std::vector<perception::FlipChoice> baseline = lowest_error.Resolve(t_s, posed_tags);
      for (std::size_t i = 0; i < posed_tags.size(); ++i) {
        const TagPoseCandidate& plain =
            baseline[i].use_alternative ? *posed_tags[i].pose.alternative : posed_tags[i].pose.best;
        unresolved.push_back({posed_tags[i].family, posed_tags[i].id, resolved[i].tag_size_m,
                              plain.T_CT, plain.covariance});
        flips_resolved += RotationErrorDeg(resolved[i].T_CT, truth[i]) > kFlippedTagDeg;
        flips_unresolved += RotationErrorDeg(plain.T_CT, truth[i]) > kFlippedTagDeg;
        ++posed;
        rows[i].push_back(RotationErrorDeg(plain.T_CT, truth[i]));
        observation_rows->push_back(rows[i]);
      }
      // Gravity in C as the vehicle's attitude estimate gives it: the true direction, off by
      // N(0, gravity_sigma_deg) per axis (the map's own assumption).
      perception::TagMapOnboardEstimate onboard;
      onboard.down_C = control::ExpSo3(gaussian() * map_params.gravity_sigma_deg * M_PI / 180.0) *
                       T_WC.linear().transpose() * -Eigen::Vector3d::UnitZ();
      // Odometry as a VIO gives it: the true motion since the last frame, off by the random walk
      // the map assumes (the map's odometry sigmas times sqrt(step length)), so O drifts from W.
      if (!T_OC) {
        T_OC = T_WC;
      } else {
        Eigen::Isometry3d T_step = T_WC_previous->inverse() * T_WC;
        const double step_m = T_step.translation().norm();
        T_step.translation() +=
            map_params.odometry_sigma_m_per_sqrt_m * std::sqrt(step_m) * gaussian();
        T_step.linear() = control::ExpSo3(map_params.odometry_sigma_deg_per_sqrt_m * M_PI / 180.0 *
                                          std::sqrt(step_m) * gaussian()) *
                          T_step.linear();
        T_OC = *T_OC * T_step;
      }
      T_WC_previous = T_WC;
      onboard.T_OC = T_OC;
      resolved_map.AddImage(t_s, resolved, onboard);
      unresolved_map.AddImage(t_s, unresolved, onboard);
      without_odometry_map.AddImage(t_s, resolved, {onboard.down_C, std::nullopt});
      t_axis.push_back(t_s);
      detections_per_frame.push_back(static_cast<double>(result.tags.size()));
    }
  }
  const perception::TagMapSolveSummary solve = resolved_map.Optimize();
  unresolved_map.Optimize();
  without_odometry_map.Optimize();
  const TagMapEvaluation resolved_eval = EvaluateTagMap(resolved_map, scenario.scene());
  const TagMapEvaluation unresolved_eval = EvaluateTagMap(unresolved_map, scenario.scene());
  const TagMapEvaluation without_odometry_eval =
      EvaluateTagMap(without_odometry_map, scenario.scene());
  const int tags_in_scene = 3 + field.fixed_obstacles + field.movable_obstacles;
  nlohmann::json section = {
      {"frames", frame_index},
      {"posed_tag_observations", posed},
      {"corner_error_median_px", UpperMedian(corner_errors_px)},
      {"corner_error_p90_px", Percentile90(corner_errors_px)},
      {"flip_rate_resolved", posed ? double(flips_resolved) / posed : 0.0},
      {"flip_rate_lowest_error", posed ? double(flips_unresolved) / posed : 0.0},
      {"tags_in_scene", tags_in_scene},
      {"tags_mapped", resolved_eval.tags.size()},
      {"map_rms_before_m", resolved_eval.rms_before_m},
      {"map_rms_after_m", resolved_eval.rms_after_m},
      {"map_mean_error_m",
       {resolved_eval.mean_error_m.x(), resolved_eval.mean_error_m.y(),
        resolved_eval.mean_error_m.z()}},
      {"map_flipped_tags", resolved_eval.flipped},
      {"map_rejected_observations", solve.rejected_observations},
      {"map_odometry_edges", resolved_map.odometry_edges()},
      {"without_odometry_map_rms_before_m", without_odometry_eval.rms_before_m},
      {"without_odometry_map_rms_after_m", without_odometry_eval.rms_after_m},
      {"map_solve_time_s", solve.solve_time_s},
      {"unresolved_map_rms_after_m", unresolved_eval.rms_after_m},
      {"unresolved_map_flipped_tags", unresolved_eval.flipped},
      {"map_tags", resolved_eval.PerTagJson()},
  };
  (*summary)["mapping"] = section;
  (*summary)["acceptance"] = {
      {"map_rms_within_2cm", resolved_eval.rms_after_m <= 0.02},
      {"no_flipped_tag_in_map", resolved_eval.flipped == 0},
      {"all_tags_mapped", static_cast<int>(resolved_eval.tags.size()) == tags_in_scene},
  };
  report->AddSection("Mapping pass over the tags scenario");
  report->AddParagraph("Lawn-mower: 4 lanes at 2.5 m; map errors in the origin tag's frame.");
  report->AddTable(section);
  report->AddSvg(output::SvgPlot({"Tags detected per frame", "t [s]", "tags"})
                     .AddLine("detections", t_axis, detections_per_frame)
                     .Render());
}

}  // namespace

std::vector<std::string> TagBenchSectionKeys() { return {"detection", "mapping", "missions"}; }

std::vector<std::string> SelectedTagBenchSections(const TagBenchOptions& options) {
  const std::vector<std::string> keys = TagBenchSectionKeys();
  for (const std::string& key : options.sections) {
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
      throw std::invalid_argument("bench tags: unknown section '" + key +
                                  "'; known: detection, mapping, missions");
    }
  }
  if (options.sections.empty()) return keys;
  std::vector<std::string> selected;
  for (const std::string& key : keys) {
    if (std::find(options.sections.begin(), options.sections.end(), key) !=
        options.sections.end()) {
      selected.push_back(key);
    }
  }
  return selected;
}

nlohmann::json RunTagBenchSection(const std::string& key, const TagBenchOptions& options) {
  nlohmann::json frames = nlohmann::json::array();
  nlohmann::json observations = nlohmann::json::array();
  nlohmann::json record;
  if (key == "detection") {
    record = RecordSection([&](nlohmann::json* summary, output::HtmlReport* report) {
      RunDetection(options, summary, report, &frames);
    });
  } else if (key == "mapping") {
    record = RecordSection([&](nlohmann::json* summary, output::HtmlReport* report) {
      RunMapping(options, summary, report, &observations);
    });
  } else if (key == "missions") {
    record = RecordSection([&](nlohmann::json* summary, output::HtmlReport* report) {
      RunMissionsSection(options, summary, report);
    });
  } else {
    throw std::invalid_argument("bench tags: unknown section '" + key +
                                "'; known: detection, mapping, missions");
  }
  record["section"] = key;
  record["frames"] = std::move(frames);
  record["observations"] = std::move(observations);
  return record;
}

void WriteTagBenchOutputs(const TagBenchOptions& options,
                          const std::vector<nlohmann::json>& section_records,
                          nlohmann::json* summary, output::HtmlReport* report) {
  std::optional<output::CsvWriter> frames_csv, observations_csv;
  if (!options.frames_csv_path.empty()) {
    frames_csv.emplace(options.frames_csv_path, kTagFramesCsvColumns);
  }
  if (!options.observations_csv_path.empty()) {
    observations_csv.emplace(options.observations_csv_path, kObservationsCsvColumns);
  }
  for (const nlohmann::json& record : section_records) {
    AddSectionRecord(record, summary, report);
    if (frames_csv) WriteRecordedCsvRows(record.at("frames"), &*frames_csv);
    if (observations_csv) WriteRecordedCsvRows(record.at("observations"), &*observations_csv);
  }
  if (frames_csv) frames_csv->Close();
  if (observations_csv) observations_csv->Close();
}

}  // namespace aperture::experiments
