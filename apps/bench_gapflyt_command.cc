// aperture bench gapflyt: closed-loop GapFlyt flights through randomized unknown openings per
// servo law (issue 14; seed 002 Sec. IV analog; experiments/gapflyt/gapflyt_bench.h).
//
//   aperture bench gapflyt [--trials N] [--seed S] [--laws moments,pid] [--width W --height H]
//                          [--tight-every K] [--quick] [--set mission.key=value ...]
//                          [--threads T] [--shard K/N] --out DIR
//
// --quick: one trial (the ellipse) per law (a smoke test of ~10 s). Writes DIR/summary.json,
// DIR/trials.csv, DIR/report.html, or with --shard K/N the K-th block of the trials for
// `aperture bench merge` (experiments/bench/monte_carlo_run.h).
#include <memory>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "experiments/gapflyt/gapflyt_monte_carlo_bench.h"
#include "perception/graph/front_end_registry.h"

namespace aperture::apps {
namespace {

struct BenchGapflytOptions {
  CommonOptions common;
  MonteCarloCommandOptions monte_carlo;
  experiments::GapflytBenchOptions bench;
  std::string laws;
  bool quick = false;
};

void RunBenchGapflyt(BenchGapflytOptions options, output::OutputFolder& out) {
  std::vector<std::string> set_items;
  for (const std::string& item : options.common.set_items) {
    (item.rfind("mission.", 0) == 0 ? options.bench.mission_set_items : set_items).push_back(item);
  }
  if (!set_items.empty() || !options.common.config_files.empty()) {
    throw std::invalid_argument("bench gapflyt: only --set mission.<key>=<value> is read (got '" +
                                (set_items.empty() ? std::string("--config") : set_items.front()) +
                                "'); the scene is drawn per trial");
  }
  if (!options.laws.empty()) options.bench.laws = perception::SplitFrontEndList(options.laws);
  if (options.quick) options.bench.trials = 1;  // trial 0: the ellipse
  RunMonteCarloCommand(experiments::kGapflytBenchName,
                       experiments::GapflytBenchConfiguration(options.bench, options.quick),
                       options.monte_carlo, out);
}

}  // namespace

void AddBenchGapflytCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchGapflytOptions>();
  CLI::App* command = bench.add_subcommand(
      "gapflyt",
      "GapFlyt flights through randomized unknown openings per servo law (seed 002 Sec. IV)");
  command->add_option("--trials", options->bench.trials, "Trials per law (shapes cycle)")
      ->check(IntegerIn(1));
  AddSeedOption(command, &options->bench.seed, "Seed of every trial's random choices");
  command->add_option("--laws", options->laws, "Comma-separated servo laws (moments,pid)")
      ->check(CommaListOf({"moments", "pid"}));
  command->add_option("--width", options->bench.width, "Forward camera image width [px]")
      ->check(IntegerIn(32, 8192));
  command->add_option("--height", options->bench.height, "Forward camera image height [px]")
      ->check(IntegerIn(24, 8192));
  command
      ->add_option("--tight-every", options->bench.tight_every,
                   "Every K-th round of the five shapes is tight (0: none)")
      ->check(IntegerIn(0));
  command->add_flag("--quick", options->quick, "One trial (the ellipse) per law (smoke test)");
  AddCommonOptions(command, &options->common);
  AddMonteCarloOptions(command, &options->monte_carlo);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] { RunBenchGapflyt(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
