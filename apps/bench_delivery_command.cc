// aperture bench delivery: seeded SITL flights of paper D's ground-robot mission on random `tags`
// fields (issue 16's closed loop: the first-aid kit on the goal).
//
//   aperture bench delivery --out DIR [--trials 50] [--seed S] [--mission deliver|follow]
//                           [--configurations relocalize,open_loop] [--set tags.KEY=V]
//                           [--set mission.KEY=V] [--threads T] [--shard K/N]
//
// Writes DIR/summary.json (delivery, acceptance; see experiments/tags/delivery_bench.h),
// DIR/flights.csv (one row per flight) and DIR/report.html, or with --shard K/N the K-th block of
// the fields for `aperture bench merge`.
#include <memory>
#include <string>
#include <vector>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "experiments/tags/delivery_monte_carlo_bench.h"
#include "output/output_folder.h"

namespace aperture::apps {
namespace {

struct BenchDeliveryOptions {
  std::string out_dir;
  bool overwrite = false;
  MonteCarloCommandOptions monte_carlo;
  experiments::DeliveryBenchOptions bench;
};

}  // namespace

void AddBenchDeliveryCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchDeliveryOptions>();
  CLI::App* command = bench.add_subcommand(
      "delivery", "Ground-robot missions on random tag fields: the kit on the goal (paper D)");
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  AddOverwriteFlag(command, &options->overwrite);
  command->add_option("--trials", options->bench.trials, "Fields (seeds --seed ..)")
      ->check(IntegerIn(1));
  AddSeedOption(command, &options->bench.first_seed, "Seed of the first field");
  command
      ->add_option("--mission", options->bench.mission,
                   "deliver (mapping flight, plan on the map) or follow (plan on the truth)")
      ->check(CLI::IsMember({"deliver", "follow"}));
  command
      ->add_option("--configurations", options->bench.configurations,
                   "relocalize,open_loop (default relocalize)")
      ->delimiter(',')
      ->check(CLI::IsMember({"relocalize", "open_loop"}));
  command->add_option("--set", options->bench.set_items,
                      "Scenario or mission override, e.g. tags.movable_obstacles=6, "
                      "mission.robot_drift_scale_sigma=0.05");
  AddMonteCarloOptions(command, &options->monte_carlo);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->out_dir, options->overwrite);
    output::RunAndWriteSummary(out, [&] {
      RunMonteCarloCommand(experiments::kDeliveryBenchName,
                           experiments::DeliveryBenchConfiguration(options->bench),
                           options->monte_carlo, out);
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
