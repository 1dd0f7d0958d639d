#pragma once
// The SITL CPU profile (sim/sitl/sitl_runner.h SitlCpuProfile, sim/render/render_profile.h) in
// summary.json: `aperture sim`'s timing.cpu and `aperture bench gap`'s per-trial records and
// their sum. Shape:
//   {"definition": ..., "sim_time_s": S, "total_s": T, "renders": N,
//    "stages_s": {dynamics, render, perception, control, collision, hooks, other},
//    "render_stages_s": {setup, centers, supersampling, leds, blur, noise, other},
//    "ms_per_sim_s": {total, every stage and render stage as render_<name>}}
// "other" = total minus the named stages (of the SITL: what ran beside them, e.g. a background
// video encoder; of the renderer: the render section outside the stages, the frame queue).
#include <nlohmann/json.hpp>
#include <vector>

#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

nlohmann::json SitlCpuProfileToJson(const sim::SitlCpuProfile& profile, double sim_time_s);

// The sum of profiles written by SitlCpuProfileToJson (e.g. a bench's trials): every second,
// sim_time_s and renders summed, ms_per_sim_s recomputed from the sums. Empty: null.
nlohmann::json SumSitlCpuProfiles(const std::vector<nlohmann::json>& profiles);

}  // namespace aperture::experiments
