#include "experiments/bench/sitl_profile_json.h"

#include <string>

namespace aperture::experiments {
namespace {

constexpr const char* kSitlCpuProfileDefinition =
    "process CPU seconds (every thread) per stage of the SITL loop, exact while the flight is "
    "alone in the process (aperture sim; a bench on --threads 1); perception = Autopilot::OnFrame, "
    "control = the other Autopilot calls; render_stages_s split render; other = total minus the "
    "named stages";

// ms of CPU per simulated second of every stage, from the "stages_s" / "render_stages_s" sums.
void PutMsPerSimSecond(nlohmann::json* profile) {
  const double sim_time_s = (*profile)["sim_time_s"].get<double>();
  const auto per_sim_s = [sim_time_s](double s) {
    return sim_time_s > 0.0 ? 1e3 * s / sim_time_s : 0.0;
  };
  nlohmann::json ms = {{"total", per_sim_s((*profile)["total_s"].get<double>())}};
  for (const auto& [stage, seconds] : (*profile)["stages_s"].items()) {
    ms[stage] = per_sim_s(seconds.get<double>());
  }
  for (const auto& [stage, seconds] : (*profile)["render_stages_s"].items()) {
    ms["render_" + stage] = per_sim_s(seconds.get<double>());
  }
  (*profile)["ms_per_sim_s"] = ms;
}

// Adds every number of `from` to the same key of *to (objects recursively).
void AddNumbers(const nlohmann::json& from, nlohmann::json* to) {
  for (const auto& [key, value] : from.items()) {
    if (value.is_object()) {
      AddNumbers(value, &(*to)[key]);
    } else if (value.is_number()) {
      (*to)[key] = (to->contains(key) ? (*to)[key].get<double>() : 0.0) + value.get<double>();
    }
  }
}

}  // namespace

nlohmann::json SitlCpuProfileToJson(const sim::SitlCpuProfile& profile, double sim_time_s) {
  const sim::RenderProfile& render = profile.render;
  nlohmann::json json = {{"definition", kSitlCpuProfileDefinition},
                         {"sim_time_s", sim_time_s},
                         {"total_s", profile.total_s},
                         {"renders", render.renders},
                         {"stages_s",
                          {{"dynamics", profile.dynamics_s},
                           {"render", profile.render_s},
                           {"perception", profile.perception_s},
                           {"control", profile.control_s},
                           {"collision", profile.collision_s},
                           {"hooks", profile.hooks_s},
                           {"other", profile.total_s - profile.stages_s()}}},
                         {"render_stages_s",
                          {{"setup", render.setup_s},
                           {"centers", render.centers_s},
                           {"supersampling", render.supersampling_s},
                           {"leds", render.leds_s},
                           {"blur", render.blur_s},
                           {"noise", render.noise_s},
                           {"other", profile.render_s - render.total_s()}}}};
  PutMsPerSimSecond(&json);
  return json;
}

nlohmann::json SumSitlCpuProfiles(const std::vector<nlohmann::json>& profiles) {
  if (profiles.empty()) return nullptr;
  nlohmann::json sum = nlohmann::json::object();
  for (const nlohmann::json& profile : profiles) {
    nlohmann::json numbers = profile;
    numbers.erase("ms_per_sim_s");
    AddNumbers(numbers, &sum);
  }
  sum["definition"] = profiles.front()["definition"];
  sum["renders"] = static_cast<long long>(sum["renders"].get<double>() + 0.5);
  PutMsPerSimSecond(&sum);
  return sum;
}

}  // namespace aperture::experiments
