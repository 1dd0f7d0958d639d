// GapflytBenchOptions and GapflytTrialRecord as JSON (gapflyt_bench.h): the configuration and the
// trial records of `aperture bench gapflyt` as a Monte-Carlo bench.
#include <stdexcept>

#include "experiments/gapflyt/gapflyt_bench.h"
#include "output/json_eigen.h"

namespace aperture::experiments {

nlohmann::json GapflytBenchOptionsToJson(const GapflytBenchOptions& o) {
  const GapflytTrialRanges& r = o.ranges;
  return {{"trials", o.trials},
          {"seed", o.seed},
          {"laws", o.laws},
          {"ranges",
           {{"foreground_x_m", output::EigenToJson(r.foreground_x_m)},
            {"background_x_m", output::EigenToJson(r.background_x_m)},
            {"width_m", output::EigenToJson(r.width_m)},
            {"height_m", output::EigenToJson(r.height_m)},
            {"max_offset_m", r.max_offset_m}}},
          {"tight_every", o.tight_every},
          {"tight_margin_m", o.tight_margin_m},
          {"width", o.width},
          {"height", o.height},
          {"duration_s", o.duration_s},
          {"mission_set_items", o.mission_set_items}};
}

GapflytBenchOptions GapflytBenchOptionsFromJson(const nlohmann::json& json) {
  try {
    GapflytBenchOptions o;
    o.trials = json.at("trials").get<int>();
    o.seed = json.at("seed").get<std::uint64_t>();
    o.laws = json.at("laws").get<std::vector<std::string>>();
    const nlohmann::json& r = json.at("ranges");
    o.ranges.foreground_x_m = output::JsonToVector<2>(r.at("foreground_x_m"));
    o.ranges.background_x_m = output::JsonToVector<2>(r.at("background_x_m"));
    o.ranges.width_m = output::JsonToVector<2>(r.at("width_m"));
    o.ranges.height_m = output::JsonToVector<2>(r.at("height_m"));
    o.ranges.max_offset_m = r.at("max_offset_m").get<double>();
    o.tight_every = json.at("tight_every").get<int>();
    o.tight_margin_m = json.at("tight_margin_m").get<double>();
    o.width = json.at("width").get<int>();
    o.height = json.at("height").get<int>();
    o.duration_s = json.at("duration_s").get<double>();
    o.mission_set_items = json.at("mission_set_items").get<std::vector<std::string>>();
    return o;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("bench gapflyt options: ") + e.what());
  }
}

nlohmann::json GapflytTrialRecordToJson(const GapflytTrialRecord& t) {
  const GapflytTrialConfig& c = t.config;
  return {{"trial", c.trial},
          {"shape", c.shape},
          {"scene_seed", c.scene_seed},
          {"foreground_x_m", c.foreground_x_m},
          {"background_x_m", c.background_x_m},
          {"size_m", output::EigenToJson(c.size_m)},
          {"center_m", output::EigenToJson(c.center_m)},
          {"tight", c.tight},
          {"law", t.law},
          {"passed", t.passed},
          {"seed002_success", t.seed002_success},
          {"figures", t.figures},
          {"sim_time_s", t.sim_time_s},
          {"wall_time_s", t.wall_time_s}};
}

GapflytTrialRecord GapflytTrialRecordFromJson(const nlohmann::json& json) {
  try {
    GapflytTrialRecord t;
    GapflytTrialConfig& c = t.config;
    c.trial = json.at("trial").get<int>();
    c.shape = json.at("shape").get<std::string>();
    c.scene_seed = json.at("scene_seed").get<std::uint64_t>();
    c.foreground_x_m = json.at("foreground_x_m").get<double>();
    c.background_x_m = json.at("background_x_m").get<double>();
    c.size_m = output::JsonToVector<2>(json.at("size_m"));
    c.center_m = output::JsonToVector<2>(json.at("center_m"));
    c.tight = json.at("tight").get<bool>();
    t.law = json.at("law").get<std::string>();
    t.passed = json.at("passed").get<bool>();
    t.seed002_success = json.at("seed002_success").get<bool>();
    t.figures = json.at("figures");
    t.sim_time_s = json.at("sim_time_s").get<double>();
    t.wall_time_s = json.at("wall_time_s").get<double>();
    return t;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("gapflyt trial record: ") + e.what());
  }
}

}  // namespace aperture::experiments
