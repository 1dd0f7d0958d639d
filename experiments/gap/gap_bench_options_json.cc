// GapBenchOptionsToJson / GapBenchOptionsFromJson (gap_bench.h).
#include <stdexcept>

#include "experiments/gap/gap_bench.h"
#include "output/json_fields.h"

namespace aperture::experiments {
namespace {

// The JSON keys of the options (output/json_fields.h); `threads` does not change a result.
constexpr auto kGapTrialRangesFields = [](auto& f, auto& r) {
  f("min_roll_deg", r.min_roll_deg);
  f("max_roll_deg", r.max_roll_deg);
  f("max_pitch_deg", r.max_pitch_deg);
  f("start_offset_m", r.start_offset_m);
  f("max_start_yaw_deg", r.max_start_yaw_deg);
  f("imu_noise_scale", r.imu_noise_scale);
  f("accel_bias_sigma_mps2", r.accel_bias_sigma_mps2);
  f("gyro_bias_sigma_radps", r.gyro_bias_sigma_radps);
  f("max_drop_probability", r.max_drop_probability);
  f("exposure_s", r.exposure_s);
  f("motion_blur_subframes", r.motion_blur_subframes);
};

constexpr auto kHoverCriteriaFields = [](auto& f, auto& h) {
  f("window_s", h.window_s);
  f("max_speed_mps", h.max_speed_mps);
  f("max_tilt_deg", h.max_tilt_deg);
  f("max_rate_radps", h.max_rate_radps);
  f("min_height_m", h.min_height_m);
};

constexpr auto kGapBenchOptionsFields = [](auto& f, auto& o) {
  f("trials", o.trials);
  f("seed", o.seed);
  f("first_trial", o.first_trial);
  f("duration_s", o.duration_s);
  f("render_cameras", o.render_cameras);
  f("render_ignored_frames", o.render_ignored_frames);
  f("detector_sequences", o.detector_sequences);
  f("paper_configuration", o.paper_configuration);
  f("vehicle_mismatch", o.vehicle.mismatch);  // the bounds: VehicleMismatchBounds' defaults
  f("paper_vehicle", o.paper_vehicle);
  f("config_files", o.config_files);
  f("set_items", o.set_items);
};

}  // namespace

nlohmann::json GapBenchOptionsToJson(const GapBenchOptions& o) {
  nlohmann::json json = output::FieldsToJson(o, kGapBenchOptionsFields);
  json["ranges"] = output::FieldsToJson(o.ranges, kGapTrialRangesFields);
  json["hover_criteria"] = output::FieldsToJson(o.hover, kHoverCriteriaFields);
  json["detector_ranges"] = GapDetectorSequenceRangesToJson(o.detector_ranges);
  return json;
}

GapBenchOptions GapBenchOptionsFromJson(const nlohmann::json& json) {
  try {
    auto o = output::FieldsFromJson<GapBenchOptions>(json, kGapBenchOptionsFields);
    o.ranges = output::FieldsFromJson<GapTrialRanges>(json.at("ranges"), kGapTrialRangesFields);
    o.hover =
        output::FieldsFromJson<HoverCriteria>(json.at("hover_criteria"), kHoverCriteriaFields);
    o.detector_ranges = GapDetectorSequenceRangesFromJson(json.at("detector_ranges"));
    o.threads = 0;
    return o;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("bench gap options: ") + e.what());
  }
}

}  // namespace aperture::experiments
