#pragma once
// `aperture bench tags --section missions` (issue 16): paper D's ground-robot mission planner
// (planning/ground_mission/ground_mission_planner.h) on random scenes, Sec. D.7.1:
//   timing      Fig. D.13's analog: on the slalom field (4 x 6 m, two walls) 50 scenes per
//               number of movable obstacles 2, 4, 6, 8, 10 (10 with quick); median and largest
//               planning time and partial missions expanded per number (measured: under "timing")
//   solve rate  of those 250 scenes (the paper: 248 of 250), each solved mission checked
//   optimality  Alg. 2 against the exhaustive search over every order of every subset on 100
//               small scenes (20 with quick: the passage field, 2-4 obstacles around its passage)
// Acceptance: >= 99 % solved, Alg. 2 equal to the exhaustive search on every compared scene.
#include <nlohmann/json.hpp>

#include "experiments/tags/tag_bench.h"
#include "output/html_report.h"

namespace aperture::experiments {

void RunMissionsSection(const TagBenchOptions& options, nlohmann::json* summary,
                        output::HtmlReport* report);

}  // namespace aperture::experiments
