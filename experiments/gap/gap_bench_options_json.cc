// GapBenchOptionsToJson / GapBenchOptionsFromJson (gap_bench.h).
#include <stdexcept>

#include "experiments/gap/gap_bench.h"
#include "output/json_eigen.h"

namespace aperture::experiments {

nlohmann::json GapBenchOptionsToJson(const GapBenchOptions& o) {
  return {{"trials", o.trials},
          {"seed", o.seed},
          {"first_trial", o.first_trial},
          {"duration_s", o.duration_s},
          {"render_cameras", o.render_cameras},
          {"render_ignored_frames", o.render_ignored_frames},
          {"ranges",
           {{"max_roll_deg", o.ranges.max_roll_deg},
            {"max_pitch_deg", o.ranges.max_pitch_deg},
            {"start_offset_m", output::EigenToJson(o.ranges.start_offset_m)},
            {"max_start_yaw_deg", o.ranges.max_start_yaw_deg},
            {"imu_noise_scale", output::EigenToJson(o.ranges.imu_noise_scale)},
            {"accel_bias_sigma_mps2", o.ranges.accel_bias_sigma_mps2},
            {"gyro_bias_sigma_radps", o.ranges.gyro_bias_sigma_radps},
            {"max_drop_probability", o.ranges.max_drop_probability},
            {"exposure_s", output::EigenToJson(o.ranges.exposure_s)},
            {"motion_blur_subframes", o.ranges.motion_blur_subframes}}},
          {"hover_criteria",
           {{"window_s", o.hover.window_s},
            {"max_speed_mps", o.hover.max_speed_mps},
            {"max_tilt_deg", o.hover.max_tilt_deg},
            {"max_rate_radps", o.hover.max_rate_radps},
            {"min_height_m", o.hover.min_height_m}}},
          {"detector_sequences", o.detector_sequences},
          {"detector_ranges", GapDetectorSequenceRangesToJson(o.detector_ranges)},
          {"config_files", o.config_files},
          {"set_items", o.set_items}};
}

GapBenchOptions GapBenchOptionsFromJson(const nlohmann::json& json) {
  try {
    GapBenchOptions o;
    o.trials = json.at("trials").get<int>();
    o.seed = json.at("seed").get<std::uint64_t>();
    o.first_trial = json.at("first_trial").get<int>();
    o.duration_s = json.at("duration_s").get<double>();
    o.render_cameras = json.at("render_cameras").get<bool>();
    o.render_ignored_frames = json.at("render_ignored_frames").get<bool>();
    const nlohmann::json& r = json.at("ranges");
    o.ranges.max_roll_deg = r.at("max_roll_deg").get<double>();
    o.ranges.max_pitch_deg = r.at("max_pitch_deg").get<double>();
    o.ranges.start_offset_m = output::JsonToVector<3>(r.at("start_offset_m"));
    o.ranges.max_start_yaw_deg = r.at("max_start_yaw_deg").get<double>();
    o.ranges.imu_noise_scale = output::JsonToVector<2>(r.at("imu_noise_scale"));
    o.ranges.accel_bias_sigma_mps2 = r.at("accel_bias_sigma_mps2").get<double>();
    o.ranges.gyro_bias_sigma_radps = r.at("gyro_bias_sigma_radps").get<double>();
    o.ranges.max_drop_probability = r.at("max_drop_probability").get<double>();
    o.ranges.exposure_s = output::JsonToVector<2>(r.at("exposure_s"));
    o.ranges.motion_blur_subframes = r.at("motion_blur_subframes").get<int>();
    const nlohmann::json& h = json.at("hover_criteria");
    o.hover.window_s = h.at("window_s").get<double>();
    o.hover.max_speed_mps = h.at("max_speed_mps").get<double>();
    o.hover.max_tilt_deg = h.at("max_tilt_deg").get<double>();
    o.hover.max_rate_radps = h.at("max_rate_radps").get<double>();
    o.hover.min_height_m = h.at("min_height_m").get<double>();
    o.detector_sequences = json.at("detector_sequences").get<int>();
    o.detector_ranges = GapDetectorSequenceRangesFromJson(json.at("detector_ranges"));
    o.config_files = json.at("config_files").get<std::vector<std::string>>();
    o.set_items = json.at("set_items").get<std::vector<std::string>>();
    o.threads = 0;
    return o;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("bench gap options: ") + e.what());
  }
}

}  // namespace aperture::experiments
