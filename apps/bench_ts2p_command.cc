// aperture bench ts2p: TS²P gap detection and label tracking on rendered scans (issue 13; seed
// 002 Table II, Figs. 9, 12, 13, Table III analogs).
//
//   aperture bench ts2p [--trials N] [--seed S] [--methods dis_medium,deepflow,...]
//                       [--sweep-trials N] [--depth-trials N] [--tracking-trials N] [--quick]
//                       [--set ts2p.segmentation=edges ...] [--threads T] [--shard K/N] --out DIR
//
// --set ts2p.* / gap_tracker.* configure the detector (its flow.method is the sweeps' method)
// and the tracker. --quick: one trial per shape, the configured method only, no sweeps, one
// short approach (a smoke test of a few seconds). Writes DIR/summary.json, DIR/trials.csv,
// DIR/report.html (experiments/ts2p/ts2p_bench.h), or with --shard K/N the K-th block of the
// rendered scans (a trial is a scan: a detection trial with its sweeps, a depth-sweep scan or a
// tracking approach; experiments/ts2p/ts2p_monte_carlo_bench.h) for `aperture bench merge`.
#include <memory>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "experiments/ts2p/ts2p_monte_carlo_bench.h"
#include "perception/flow/dense_flow.h"
#include "perception/graph/front_end_registry.h"

namespace aperture::apps {
namespace {

struct BenchTs2pOptions {
  CommonOptions common;
  MonteCarloCommandOptions monte_carlo;
  experiments::Ts2pBenchOptions bench;
  std::string methods;
  bool quick = false;
};

void RunBenchTs2p(BenchTs2pOptions options, output::OutputFolder& out) {
  // Read here first so that a mistake is named by its file line or --set item.
  const config::ConfigTree tree = LoadConfig(options.common, "");
  experiments::ReadTs2pBenchParams(tree, &options.bench);
  if (!options.methods.empty())
    options.bench.methods = perception::SplitFrontEndList(options.methods);
  if (options.quick) {
    options.bench.trials = static_cast<int>(experiments::kTs2pShapes.size());
    if (options.methods.empty()) options.bench.methods = {options.bench.detector.flow.method};
    options.bench.sweep_trials = 0;
    options.bench.depth_trials = 0;
    options.bench.tracking_trials = 1;
    options.bench.tracking_frames = 8;
  }
  RunMonteCarloCommand(experiments::kTs2pBenchName,
                       experiments::Ts2pBenchConfiguration(options.bench, options.quick,
                                                           nlohmann::json::parse(tree.ToJson())),
                       options.monte_carlo, out);
}

}  // namespace

void AddBenchTs2pCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchTs2pOptions>();
  CLI::App* command = bench.add_subcommand(
      "ts2p",
      "TS2P gap detection per flow method and label tracking on rendered scans (seed "
      "002 Tables II, III, Figs. 9, 12, 13)");
  command->add_option("--trials", options->bench.trials, "Trials (shapes cycle through the five)")
      ->check(IntegerIn(1));
  AddSeedOption(command, &options->bench.seed, "Seed of every trial's random choices");
  command
      ->add_option("--methods", options->methods,
                   "Comma-separated flow methods for Table II (default: all)")
      ->check(CommaListOf(perception::DenseFlowMethodNames()));
  command
      ->add_option("--sweep-trials", options->bench.sweep_trials,
                   "Trials of the N and resolution sweeps (the first ones)")
      ->check(IntegerIn(0));
  command
      ->add_option("--depth-trials", options->bench.depth_trials,
                   "Trials per foreground depth of the Z_F sweep")
      ->check(IntegerIn(0));
  command
      ->add_option("--tracking-trials", options->bench.tracking_trials,
                   "Approaches of the tracking analysis")
      ->check(IntegerIn(0));
  command->add_flag("--quick", options->quick,
                    "One trial per shape with the configured method, no sweeps (smoke test)");
  AddCommonOptions(command, &options->common);
  AddMonteCarloOptions(command, &options->monte_carlo);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] { RunBenchTs2p(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
