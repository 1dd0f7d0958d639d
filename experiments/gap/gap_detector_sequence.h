#pragma once
// The detector section of `aperture bench gap` (issue 22): the patterned-gap detector
// (perception/gap/gap_detector.h) on rendered sequences flown past the gap, scored against the
// renderer's ground truth. A sequence draws the gap's inclination, a straight camera path between
// two viewpoints on the gap's side (1-6 m, up to 50 deg off its normal) flown at a constant
// speed, the camera aimed near the gap and rolled about its axis, and the exposure (motion blur
// from the path); it renders the `gap` scenario's camera at its frame rate and runs the detector
// on every frame in order, as the mission does (ROI tracking).
//
//   GapDetectorSequenceRanges ranges;
//   GapDetectorSequenceConfig config = DrawGapDetectorSequence(ranges, seed, index);
//   GapDetectorSequenceRecord record = RunGapDetectorSequence(config, base, detector_params);
//
// Every frame is scored by both poses a mission can use: the gap in the camera, T_CG (what the
// render tests check), and the camera in the gap frame, T_GC (what the gap mission plans with):
// a rotation error e moves p_GC by ~e * distance while p_CG does not move.
#include <Eigen/Geometry>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "perception/gap/gap_detector.h"
#include "sim/scenario/scenario_params.h"

namespace aperture::experiments {

struct GapDetectorSequenceRanges {
  double max_roll_deg = 60.0;   // gap roll uniform in [0, max] (the issue: to 60 deg)
  double max_pitch_deg = 30.0;  // gap pitch uniform in [0, max]
  // The path's two ends: distances to the opening's centre uniform in this range [m], directions
  // uniform on the cap within max_view_angle_deg of the gap's normal, on the camera's side.
  Eigen::Vector2d distance_m = Eigen::Vector2d(1.0, 6.0);
  double max_view_angle_deg = 50.0;
  double max_speed_mps = 3.0;  // camera speed uniform in [0, max]
  double duration_s = 1.0;     // per sequence, or until the path's far end is reached
  double max_aim_offset_deg = 20.0;  // camera axis off the line of sight to the gap, per axis
  double max_camera_roll_deg = 30.0;  // camera roll about its axis, uniform in [-max, max]
  Eigen::Vector2d exposure_s = Eigen::Vector2d(0.5e-3, 4.0e-3);  // uniform, as the flights
  int motion_blur_subframes = 3;  // renders per frame over the exposure (1 = no blur)

  // Throws std::invalid_argument naming the field for negative or non-finite values, inverted
  // ranges, a distance range not above 0, angles of 90 deg or more, or subframes < 1.
  void Validate() const;
};

struct GapDetectorSequenceConfig {
  int index = 0;
  std::uint64_t seed = 0;  // seeds the scenario (textures, camera noise)
  double roll_deg = 0.0;
  double pitch_deg = 0.0;
  Eigen::Vector3d start_p_GC_m = Eigen::Vector3d::Zero();  // camera at t = 0, in the gap frame
  Eigen::Vector3d end_p_GC_m = Eigen::Vector3d::Zero();    // far end of the path
  double speed_mps = 0.0;
  double duration_s = 0.0;  // flown time: min(ranges.duration_s, path length / speed)
  Eigen::Vector2d aim_offset_deg = Eigen::Vector2d::Zero();  // about the camera's y and x axes
  double camera_roll_deg = 0.0;
  double exposure_s = 0.0;
  int motion_blur_subframes = 1;
};

// Sequence `index` of a bench run with `bench_seed`: a pure function of both.
// Throws std::invalid_argument for invalid ranges or a negative index.
GapDetectorSequenceConfig DrawGapDetectorSequence(const GapDetectorSequenceRanges& ranges,
                                                  std::uint64_t bench_seed, int index);

// The errors of a detected pose against the truth, after resolving the pattern's symmetry
// (perception::NearestGapLabelling).
struct GapPoseError {
  double T_CG_position_m = 0.0;  // |p_CG - p_CG_true|
  double T_GC_position_m = 0.0;  // |p_GC - p_GC_true|, the camera in the gap frame
  double rotation_deg = 0.0;     // angle of R_CG_true^T R_CG
};
GapPoseError GapPoseErrorOf(const Eigen::Isometry3d& T_CG, const Eigen::Isometry3d& T_CG_true);

struct GapDetectorFrameRecord {
  int frame = 0;
  double t_s = 0.0;          // mid-exposure time from the sequence's start
  double distance_m = 0.0;   // camera to the opening's centre
  double view_angle_deg = 0.0;  // between the gap's normal and the line of sight to its centre
  bool in_view = false;      // the whole pattern in the image, not hidden (GapPatternInView)
  perception::GapDetectionStatus status = perception::GapDetectionStatus::kNoCandidate;
  bool from_roi = false;
  GapPoseError error;        // NaN without a detection
};

struct GapDetectorSequenceRecord {
  GapDetectorSequenceConfig config;
  std::vector<GapDetectorFrameRecord> frames;
  std::string error;  // non-empty if the sequence threw (the frames before it are kept)
  double wall_time_s = 0.0;
};

// Renders and detects one sequence in the scenario `base` (the bench's `gap` scenario: its
// camera, scene and sensor effects; the gap inclination, seed and exposure come from `config`).
// Exceptions of the renderer or detector are recorded in `error`.
GapDetectorSequenceRecord RunGapDetectorSequence(const GapDetectorSequenceConfig& config,
                                                 const sim::ScenarioParams& base,
                                                 const perception::GapDetectorParams& detector);

// The complete record as JSON and back (shards store it for `aperture bench merge`); NaN stays
// exact in CBOR. std::invalid_argument naming a missing or malformed key.
nlohmann::json GapDetectorSequenceRecordToJson(const GapDetectorSequenceRecord& record);
GapDetectorSequenceRecord GapDetectorSequenceRecordFromJson(const nlohmann::json& json);

nlohmann::json GapDetectorSequenceRangesToJson(const GapDetectorSequenceRanges& ranges);
GapDetectorSequenceRanges GapDetectorSequenceRangesFromJson(const nlohmann::json& json);

}  // namespace aperture::experiments
