#include "experiments/gap/gap_detector_sequence.h"

#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

#include "control/constants.h"
#include "control/require.h"
#include "output/json_fields.h"
#include "sim/scenario/scenario.h"
#include "sim/scene/counter_hash.h"
#include "sim/scene/gap_pattern_object.h"

namespace aperture::experiments {
namespace {

using control::kDegToRad;
using control::kNaN;

void RequireAngle(double deg, const std::string& field) {
  control::Require(std::isfinite(deg) && deg >= 0.0 && deg < 90.0,
                   "GapDetectorSequenceRanges." + field, "must be in [0, 90) deg");
}

void RequireInterval(const Eigen::Vector2d& range, double min, const std::string& field) {
  control::Require(range.allFinite() && range.x() >= min && range.x() <= range.y(),
                   "GapDetectorSequenceRanges." + field,
                   "must be a finite range [lo, hi] with " + std::to_string(min) + " <= lo <= hi");
}

Eigen::Vector3d DirectionOfTravel(const GapDetectorSequenceConfig& c) {
  const Eigen::Vector3d path = c.end_p_GC_m - c.start_p_GC_m;
  return path.norm() > 0.0 ? Eigen::Vector3d(path.normalized()) : Eigen::Vector3d::Zero();
}

// The camera at time t [s] of the sequence (the straight path, extended linearly beyond its ends
// for the exposure's subframes): aimed at the opening's centre with image-down along -z_W as
// far as the line of sight allows, then turned by the aim offset and rolled about its axis.
Eigen::Isometry3d CameraPose(const GapDetectorSequenceConfig& c, const Eigen::Isometry3d& T_WG,
                             double t_s) {
  const Eigen::Vector3d p_WC =
      T_WG * (c.start_p_GC_m + c.speed_mps * t_s * DirectionOfTravel(c));
  const Eigen::Vector3d z_C = (T_WG.translation() - p_WC).normalized();
  Eigen::Vector3d x_C = z_C.cross(Eigen::Vector3d::UnitZ());
  if (x_C.norm() < 1e-6) x_C = z_C.cross(Eigen::Vector3d::UnitX());
  x_C.normalize();
  Eigen::Matrix3d R_WC;
  R_WC << x_C, z_C.cross(x_C), z_C;
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  T_WC.linear() = R_WC *
                  Eigen::AngleAxisd(c.aim_offset_deg.x() * kDegToRad, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(c.aim_offset_deg.y() * kDegToRad, Eigen::Vector3d::UnitX()) *
                  Eigen::AngleAxisd(c.camera_roll_deg * kDegToRad, Eigen::Vector3d::UnitZ());
  T_WC.translation() = p_WC;
  return T_WC;
}

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) / kDegToRad;
}

}  // namespace

void GapDetectorSequenceRanges::Validate() const {
  RequireAngle(max_roll_deg, "max_roll_deg");
  RequireAngle(max_pitch_deg, "max_pitch_deg");
  RequireInterval(distance_m, 0.0, "distance_m");
  control::Require(distance_m.x() > 0.0, "GapDetectorSequenceRanges.distance_m",
                   "must start above 0 m");
  RequireAngle(max_view_angle_deg, "max_view_angle_deg");
  control::Require(std::isfinite(max_speed_mps) && max_speed_mps >= 0.0,
                   "GapDetectorSequenceRanges.max_speed_mps", "must be finite and >= 0");
  control::Require(std::isfinite(duration_s) && duration_s > 0.0,
                   "GapDetectorSequenceRanges.duration_s", "must be finite and > 0");
  RequireAngle(max_aim_offset_deg, "max_aim_offset_deg");
  RequireAngle(max_camera_roll_deg, "max_camera_roll_deg");
  RequireInterval(exposure_s, 0.0, "exposure_s");
  control::Require(motion_blur_subframes >= 1, "GapDetectorSequenceRanges.motion_blur_subframes",
                   "must be >= 1");
}

GapDetectorSequenceConfig DrawGapDetectorSequence(const GapDetectorSequenceRanges& ranges,
                                                  std::uint64_t bench_seed, int index) {
  ranges.Validate();
  if (index < 0) {
    throw std::invalid_argument("DrawGapDetectorSequence: sequence index " +
                                std::to_string(index) + " must be >= 0");
  }
  GapDetectorSequenceConfig c;
  c.index = index;
  c.seed = sim::HashCounters(bench_seed, 0x6761705F64657463ull,  // "gap_detc"
                             static_cast<std::uint64_t>(index));
  // A fixed order of draws from the sequence's own generator (libstdc++'s algorithms are fixed).
  std::mt19937_64 rng(sim::MixBits(c.seed));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  c.roll_deg = uniform(0.0, ranges.max_roll_deg);
  c.pitch_deg = uniform(0.0, ranges.max_pitch_deg);
  // Uniform on the spherical cap around -z_G (the camera's side of the pattern).
  const auto viewpoint = [&] {
    const double distance = uniform(ranges.distance_m.x(), ranges.distance_m.y());
    const double cos_angle = uniform(std::cos(ranges.max_view_angle_deg * kDegToRad), 1.0);
    const double azimuth = uniform(0.0, 2.0 * M_PI);
    const double sin_angle = std::sqrt(1.0 - cos_angle * cos_angle);
    return Eigen::Vector3d(distance * sin_angle * std::cos(azimuth),
                           distance * sin_angle * std::sin(azimuth), -distance * cos_angle);
  };
  c.start_p_GC_m = viewpoint();
  c.end_p_GC_m = viewpoint();
  c.speed_mps = uniform(0.0, ranges.max_speed_mps);
  const double length_m = (c.end_p_GC_m - c.start_p_GC_m).norm();
  c.duration_s = c.speed_mps > 0.0 ? std::min(ranges.duration_s, length_m / c.speed_mps)
                                   : ranges.duration_s;
  const double aim = ranges.max_aim_offset_deg;
  c.aim_offset_deg.x() = uniform(-aim, aim);
  c.aim_offset_deg.y() = uniform(-aim, aim);
  c.camera_roll_deg = uniform(-ranges.max_camera_roll_deg, ranges.max_camera_roll_deg);
  c.exposure_s = uniform(ranges.exposure_s.x(), ranges.exposure_s.y());
  c.motion_blur_subframes = ranges.motion_blur_subframes;
  return c;
}

GapPoseError GapPoseErrorOf(const Eigen::Isometry3d& T_CG, const Eigen::Isometry3d& T_CG_true) {
  const Eigen::Isometry3d labelled = perception::NearestGapLabelling(T_CG, T_CG_true.linear());
  GapPoseError e;
  e.T_CG_position_m = (labelled.translation() - T_CG_true.translation()).norm();
  e.T_GC_position_m =
      (labelled.inverse().translation() - T_CG_true.inverse().translation()).norm();
  e.rotation_deg =
      Eigen::AngleAxisd(T_CG_true.linear().transpose() * labelled.linear()).angle() / kDegToRad;
  return e;
}

GapDetectorSequenceRecord RunGapDetectorSequence(const GapDetectorSequenceConfig& config,
                                                 const sim::ScenarioParams& base,
                                                 const perception::GapDetectorParams& detector) {
  const auto start = std::chrono::steady_clock::now();
  GapDetectorSequenceRecord record;
  record.config = config;
  try {
    sim::ScenarioParams params = base;
    params.seed = config.seed;
    params.gap.roll_deg = config.roll_deg;
    params.gap.pitch_deg = config.pitch_deg;
    for (auto& [name, camera] : params.cameras) {
      camera.exposure_s = config.exposure_s;
      camera.motion_blur_subframes = config.motion_blur_subframes;
    }
    const sim::Scenario scenario = sim::BuildScenario(params);
    const int gap_id = scenario.scene().FindId("gap");
    if (gap_id < 0) {
      throw std::invalid_argument("the scenario '" + scenario.kind() + "' has no object 'gap'");
    }
    const Eigen::Isometry3d T_WG = scenario.scene().object(gap_id).T_WO;
    const sim::ScenarioCamera& camera = scenario.render_camera();
    perception::GapDetector gap_detector(detector, camera.model);
    sim::RayCaster caster;
    sim::RenderOptions options = camera.render;
    options.ground_truth = true;  // the object ids tell whether the pattern shows
    const auto T_WC_at = [&](double t_s) { return CameraPose(config, T_WG, t_s); };
    const int frames = 1 + static_cast<int>(std::floor(config.duration_s * camera.rate_hz + 1e-9));
    for (int k = 0; k < frames; ++k) {
      const double t_s = k / camera.rate_hz;
      const sim::CapturedFrame captured = camera.effects.Capture(
          caster, scenario.scene(), *camera.model, T_WC_at, t_s, k, options);
      const Eigen::Isometry3d T_CG_true = T_WC_at(t_s).inverse() * T_WG;
      GapDetectorFrameRecord f;
      f.frame = k;
      f.t_s = t_s;
      f.distance_m = T_CG_true.translation().norm();
      // z_G in C against the line of sight to the centre (p_CG): 0 when seen head-on.
      f.view_angle_deg = AngleDeg(T_CG_true.linear().col(2), T_CG_true.translation());
      f.in_view =
          sim::GapPatternInView(*camera.model, detector, T_CG_true, captured.object_id, gap_id);
      const perception::GapDetection d = gap_detector.Detect(captured.frame.image);
      f.status = d.status;
      f.from_roi = d.from_roi;
      f.error = d.detected() ? GapPoseErrorOf(d.T_CG, T_CG_true)
                             : GapPoseError{kNaN, kNaN, kNaN};
      record.frames.push_back(f);
    }
  } catch (const std::exception& e) {
    record.error = e.what();
  }
  record.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return record;
}

namespace {

// The JSON keys of each record struct (output/json_fields.h).
constexpr auto kDetectorRangesFields = [](auto& f, auto& r) {
  f("max_roll_deg", r.max_roll_deg);
  f("max_pitch_deg", r.max_pitch_deg);
  f("distance_m", r.distance_m);
  f("max_view_angle_deg", r.max_view_angle_deg);
  f("max_speed_mps", r.max_speed_mps);
  f("duration_s", r.duration_s);
  f("max_aim_offset_deg", r.max_aim_offset_deg);
  f("max_camera_roll_deg", r.max_camera_roll_deg);
  f("exposure_s", r.exposure_s);
  f("motion_blur_subframes", r.motion_blur_subframes);
};

constexpr auto kDetectorSequenceFields = [](auto& f, auto& r) {
  f("detector_sequence", r.config.index);
  f("seed", r.config.seed);
  f("roll_deg", r.config.roll_deg);
  f("pitch_deg", r.config.pitch_deg);
  f("start_p_GC_m", r.config.start_p_GC_m);
  f("end_p_GC_m", r.config.end_p_GC_m);
  f("speed_mps", r.config.speed_mps);
  f("duration_s", r.config.duration_s);
  f("aim_offset_deg", r.config.aim_offset_deg);
  f("camera_roll_deg", r.config.camera_roll_deg);
  f("exposure_s", r.config.exposure_s);
  f("motion_blur_subframes", r.config.motion_blur_subframes);
  f("error", r.error);
  f("wall_time_s", r.wall_time_s);
};

constexpr auto kDetectorFrameFields = [](auto& f, auto& r) {
  f("frame", r.frame);
  f("t_s", r.t_s);
  f("distance_m", r.distance_m);
  f("view_angle_deg", r.view_angle_deg);
  f("in_view", r.in_view);
  f("status", r.status, perception::GapDetectionStatusNames());
  f("from_roi", r.from_roi);
  f("T_CG_position_error_m", r.error.T_CG_position_m);
  f("T_GC_position_error_m", r.error.T_GC_position_m);
  f("rotation_error_deg", r.error.rotation_deg);
};

}  // namespace

nlohmann::json GapDetectorSequenceRangesToJson(const GapDetectorSequenceRanges& ranges) {
  return output::FieldsToJson(ranges, kDetectorRangesFields);
}

GapDetectorSequenceRanges GapDetectorSequenceRangesFromJson(const nlohmann::json& json) {
  try {
    return output::FieldsFromJson<GapDetectorSequenceRanges>(json, kDetectorRangesFields);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("bench gap detector ranges: ") + e.what());
  }
}

nlohmann::json GapDetectorSequenceRecordToJson(const GapDetectorSequenceRecord& record) {
  nlohmann::json json = output::FieldsToJson(record, kDetectorSequenceFields);
  json["frames"] = nlohmann::json::array();
  for (const GapDetectorFrameRecord& frame : record.frames) {
    json["frames"].push_back(output::FieldsToJson(frame, kDetectorFrameFields));
  }
  return json;
}

GapDetectorSequenceRecord GapDetectorSequenceRecordFromJson(const nlohmann::json& json) {
  try {
    auto record = output::FieldsFromJson<GapDetectorSequenceRecord>(json, kDetectorSequenceFields);
    for (const nlohmann::json& frame : json.at("frames")) {
      record.frames.push_back(
          output::FieldsFromJson<GapDetectorFrameRecord>(frame, kDetectorFrameFields));
    }
    return record;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("bench gap detector sequence record: ") + e.what());
  }
}

}  // namespace aperture::experiments
