#include "experiments/tags/missions_bench_section.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "experiments/bench/sample_statistics.h"
#include "output/svg_plot.h"
#include "planning/ground_mission/ground_mission_planner.h"
#include "planning/ground_mission/random_mission_scene.h"

namespace aperture::experiments {
namespace {

// Fig. D.13: 5 numbers of movable obstacles x 50 scenes = 250 scenes.
constexpr int kMovableObstacleCounts[] = {2, 4, 6, 8, 10};

// Seeds per (bench seed, count, trial), disjoint between the counts and the two scene kinds.
std::uint64_t SceneSeed(std::uint64_t bench_seed, int kind, int count, int trial) {
  return bench_seed * 1000000 + static_cast<std::uint64_t>(kind) * 100000 +
         static_cast<std::uint64_t>(count) * 1000 + static_cast<std::uint64_t>(trial);
}

}  // namespace

void RunMissionsSection(const TagBenchOptions& options, nlohmann::json* summary,
                        output::HtmlReport* report) {
  const planning::GroundMissionParams params;
  const int trials = options.quick ? 10 : 50;
  nlohmann::json timing = nlohmann::json::array();
  nlohmann::json per_count = nlohmann::json::array();
  std::vector<double> counts, median_times_ms;
  int scenes = 0, solved = 0;
  for (const int count : kMovableObstacleCounts) {
    planning::RandomMissionSceneParams scene_params;
    scene_params.field = planning::SlalomField();
    scene_params.movable_obstacles = count;
    std::vector<double> times_s, expanded, removals;
    int solved_here = 0;
    for (int trial = 0; trial < trials; ++trial) {
      const planning::GroundMission mission =
          planning::GroundMissionPlanner(
              planning::RandomMissionScene(scene_params, SceneSeed(options.seed, 0, count, trial)),
              params)
              .Plan();
      times_s.push_back(mission.solve_time_s);
      expanded.push_back(mission.missions_expanded);
      if (mission.solved()) {
        ++solved_here;
        removals.push_back(static_cast<double>(mission.removals.size()));
      }
    }
    scenes += trials;
    solved += solved_here;
    per_count.push_back({{"movable_obstacles", count},
                         {"scenes", trials},
                         {"solved", solved_here},
                         {"expanded_median", UpperMedian(expanded)},
                         {"removals_mean", FiniteOrNull(Mean(removals))}});
    timing.push_back({{"movable_obstacles", count},
                      {"planning_time_median_s", UpperMedian(times_s)},
                      {"planning_time_max_s", *std::max_element(times_s.begin(), times_s.end())}});
    counts.push_back(count);
    median_times_ms.push_back(1e3 * UpperMedian(times_s));
  }
  // Alg. 2 against the exhaustive search on small scenes.
  const int compared = options.quick ? 20 : 100;
  int equal = 0, with_removals = 0;
  std::vector<double> expanded_ratio;
  for (int trial = 0; trial < compared; ++trial) {
    planning::RandomMissionSceneParams scene_params;
    scene_params.field = planning::PassageField();
    std::tie(scene_params.region_min_W, scene_params.region_max_W) = planning::PassageRegion();
    scene_params.movable_obstacles = 2 + trial % 3;
    const planning::GroundMissionPlanner planner(
        planning::RandomMissionScene(
            scene_params, SceneSeed(options.seed, 1, scene_params.movable_obstacles, trial)),
        params);
    const planning::GroundMission planned = planner.Plan();
    const planning::GroundMission exhaustive = planner.PlanExhaustively();
    const bool same = planned.solved() == exhaustive.solved() &&
                      (!planned.solved() || std::abs(planned.cost_s - exhaustive.cost_s) <= 1e-9);
    equal += same ? 1 : 0;
    with_removals += planned.removals.empty() ? 0 : 1;
    expanded_ratio.push_back(static_cast<double>(planned.missions_expanded) /
                             exhaustive.missions_expanded);
  }
  const double solve_rate = static_cast<double>(solved) / scenes;
  nlohmann::json section = {
      {"scenes", scenes},
      {"solved", solved},
      {"solve_rate", solve_rate},
      {"per_obstacle_count", per_count},
      {"compared_scenes", compared},
      {"equal_to_exhaustive", equal},
      {"compared_with_removals", with_removals},
      {"expanded_vs_exhaustive_median", UpperMedian(expanded_ratio)},
      {"timing", timing},
  };
  (*summary)["missions"] = section;
  (*summary)["acceptance"]["missions_solved_at_least_99pct"] = solve_rate >= 0.99;
  (*summary)["acceptance"]["missions_equal_exhaustive_search"] = equal == compared;
  report->AddSection("Ground-robot missions (paper D, Alg. 2)");
  report->AddParagraph(
      "Random scenes on the slalom field per number of movable obstacles (Fig. D.13 analog), "
      "and Alg. 2 against the exhaustive search over all removal orders on small passage "
      "scenes. D.7 parameters: 0.2 m/s, 30 deg/s, 15 s per removal, 5 cm cells.");
  report->AddTable(section);
  report->AddSvg(output::SvgPlot({"Median planning time", "movable obstacles", "time [ms]"})
                     .AddLine("median", counts, median_times_ms)
                     .Render());
}

}  // namespace aperture::experiments
