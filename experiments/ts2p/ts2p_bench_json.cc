// Ts2pBenchOptions as JSON (ts2p_bench.h): the options of `aperture bench ts2p` in its
// Monte-Carlo bench's configuration (ts2p_monte_carlo_bench.h).
#include <stdexcept>

#include "experiments/ts2p/ts2p_bench.h"
#include "output/json_eigen.h"

namespace aperture::experiments {

nlohmann::json Ts2pBenchOptionsToJson(const Ts2pBenchOptions& o) {
  const Ts2pTrialRanges& r = o.ranges;
  return {{"trials", o.trials},
          {"seed", o.seed},
          {"methods", o.methods},
          {"ranges",
           {{"foreground_depth_m", output::EigenToJson(r.foreground_depth_m)},
            {"background_depth_m", output::EigenToJson(r.background_depth_m)},
            {"width_m", output::EigenToJson(r.width_m)},
            {"height_m", output::EigenToJson(r.height_m)},
            {"max_offset_m", r.max_offset_m},
            {"scan_angle_deg", output::EigenToJson(r.scan_angle_deg)}}},
          {"sweep_trials", o.sweep_trials},
          {"stacks", o.stacks},
          {"widths", o.widths},
          {"foreground_depths_m", o.foreground_depths_m},
          {"depth_trials", o.depth_trials},
          {"tracking_trials", o.tracking_trials},
          {"tracking_frames", o.tracking_frames},
          {"tracking_speed_mps", o.tracking_speed_mps}};
}

Ts2pBenchOptions Ts2pBenchOptionsFromJson(const nlohmann::json& json) {
  try {
    Ts2pBenchOptions o;
    o.trials = json.at("trials").get<int>();
    o.seed = json.at("seed").get<std::uint64_t>();
    o.methods = json.at("methods").get<std::vector<std::string>>();
    const nlohmann::json& r = json.at("ranges");
    o.ranges.foreground_depth_m = output::JsonToVector<2>(r.at("foreground_depth_m"));
    o.ranges.background_depth_m = output::JsonToVector<2>(r.at("background_depth_m"));
    o.ranges.width_m = output::JsonToVector<2>(r.at("width_m"));
    o.ranges.height_m = output::JsonToVector<2>(r.at("height_m"));
    o.ranges.max_offset_m = r.at("max_offset_m").get<double>();
    o.ranges.scan_angle_deg = output::JsonToVector<2>(r.at("scan_angle_deg"));
    o.sweep_trials = json.at("sweep_trials").get<int>();
    o.stacks = json.at("stacks").get<std::vector<int>>();
    o.widths = json.at("widths").get<std::vector<int>>();
    o.foreground_depths_m = json.at("foreground_depths_m").get<std::vector<double>>();
    o.depth_trials = json.at("depth_trials").get<int>();
    o.tracking_trials = json.at("tracking_trials").get<int>();
    o.tracking_frames = json.at("tracking_frames").get<int>();
    o.tracking_speed_mps = json.at("tracking_speed_mps").get<double>();
    return o;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("bench ts2p options: ") + e.what());
  }
}

}  // namespace aperture::experiments
