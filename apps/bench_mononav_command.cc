// aperture bench mononav: seeded SITL flights of the forest mission (issue 17; seed 003 Tables
// II and IV and the per-module timing).
//
//   aperture bench mononav --out DIR [--trials 40] [--seed S] [--duration S] [--quick]
//                          [--configurations edt,no_edt,random_waypoint]
//                          [--set forest.KEY=V] [--set mission.KEY=V] [--threads T] [--shard K/N]
//
// Writes DIR/summary.json (table_iv, table_ii, timing, acceptance; see
// experiments/mononav/mononav_bench.h), DIR/flights.csv (one row per flight) and DIR/report.html,
// or with --shard K/N the K-th block of the layouts for `aperture bench merge`.
#include <memory>
#include <string>
#include <vector>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "experiments/mononav/mononav_monte_carlo_bench.h"
#include "output/output_folder.h"

namespace aperture::apps {
namespace {

struct BenchMononavOptions {
  std::string out_dir;
  bool overwrite = false;
  MonteCarloCommandOptions monte_carlo;
  experiments::MononavBenchOptions bench;
};

}  // namespace

void AddBenchMononavCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchMononavOptions>();
  CLI::App* command = bench.add_subcommand(
      "mononav", "Forest flights of the monocular-depth mission (seed 003 Tables II, IV, timing)");
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  AddOverwriteFlag(command, &options->overwrite);
  command->add_option("--trials", options->bench.trials, "Forest layouts (seeds --seed ..)")
      ->check(IntegerIn(1));
  AddSeedOption(command, &options->bench.first_seed, "Seed of the first layout");
  command->add_option("--duration", options->bench.duration_s, "Simulated time per flight [s]")
      ->check(FiniteNumberIn(0.0, kMaxDurationS, /*min_inclusive=*/false));
  command->add_flag("--quick", options->bench.quick,
                    "One short flight (4 m, one trunk on the line), EDT only (same code paths)");
  command
      ->add_option("--configurations", options->bench.configurations,
                   "Configurations flown on every layout: edt,no_edt,random_waypoint (default "
                   "all)")
      ->delimiter(',');
  command->add_option(
      "--set", options->bench.set_items,
      "Scenario or mission override, e.g. forest.trees=30, mission.max_speed_mps=1");
  AddMonteCarloOptions(command, &options->monte_carlo);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->out_dir, options->overwrite);
    output::RunAndWriteSummary(out, [&] {
      RunMonteCarloCommand(experiments::kMononavBenchName,
                           experiments::MononavBenchConfiguration(options->bench),
                           options->monte_carlo, out);
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
