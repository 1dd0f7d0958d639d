// aperture bench ts2p: TS²P gap detection and label tracking on rendered scans (issue 13; seed
// 002 Table II, Figs. 9, 12, 13, Table III analogs).
//
//   aperture bench ts2p [--trials N] [--seed S] [--methods dis_medium,deepflow,...]
//                       [--sweep-trials N] [--depth-trials N] [--tracking-trials N] [--quick]
//                       [--set ts2p.segmentation=edges ...] --out DIR
//
// --set ts2p.* / gap_tracker.* configure the detector (its flow.method is the sweeps' method)
// and the tracker. --quick: one trial per shape, dis_medium only, short sweeps (a smoke test of
// a few seconds). Writes DIR/summary.json, DIR/trials.csv, DIR/report.html
// (experiments/ts2p/ts2p_bench.h).
#include <algorithm>
#include <iostream>
#include <memory>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "experiments/bench/monte_carlo_run.h"
#include "experiments/ts2p/ts2p_bench.h"
#include "output/progress_bar.h"
#include "perception/graph/front_end_registry.h"

namespace aperture::apps {
namespace {

struct BenchTs2pOptions {
  CommonOptions common;
  experiments::Ts2pBenchOptions bench;
  std::string methods;
  bool quick = false;
};

void RunBenchTs2p(BenchTs2pOptions options, output::OutputFolder& out) {
  const config::ConfigTree tree = LoadConfig(options.common, "");
  config::ParamReader root = tree.Reader();
  root.ReadSection("ts2p", &options.bench.detector);
  root.ReadSection("gap_tracker", &options.bench.tracker);
  root.RejectUnknownKeys();
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
  const int steps = options.bench.trials +
                    static_cast<int>(options.bench.foreground_depths_m.size()) *
                        options.bench.depth_trials +
                    options.bench.tracking_trials;
  output::ProgressBar progress("ts2p trials", static_cast<std::size_t>(std::max(steps, 1)));
  experiments::Ts2pBenchResult result;
  // Cost per rendered scan (detection, depth and tracking trials); not sharded (see
  // experiments::MonteCarloBenchRegistry::WithBuiltins).
  out.summary()["cost"] = experiments::MeasureTrialCost(steps, 0, [&](int) {
    result = experiments::RunTs2pBench(
        options.bench, [&](int done, int) { progress.Update(static_cast<std::size_t>(done)); });
  });
  progress.Finish();
  out.summary()["command"] = "bench ts2p";
  out.summary()["config"] = nlohmann::json::parse(tree.ToJson());
  out.summary()["quick"] = options.quick;
  experiments::WriteTs2pBenchOutputs(result, out);
  const nlohmann::json& summary = out.summary();
  if (summary.contains("acceptance")) {
    std::cout << "aperture bench ts2p: best " << summary["best_method"].get<std::string>() << " DR "
              << summary["acceptance"]["dr"].dump() << " AFN "
              << summary["acceptance"]["afn"].dump() << " AFP "
              << summary["acceptance"]["afp"].dump() << " at "
              << summary["acceptance"]["cpu_ms"].dump() << " ms CPU over " << options.bench.trials
              << " trials\n";
  }
}

}  // namespace

void AddBenchTs2pCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchTs2pOptions>();
  CLI::App* command = bench.add_subcommand(
      "ts2p",
      "TS2P gap detection per flow method and label tracking on rendered scans (seed "
      "002 Tables II, III, Figs. 9, 12, 13)");
  command->add_option("--trials", options->bench.trials, "Trials (shapes cycle through the five)")
      ->check(CLI::PositiveNumber);
  command->add_option("--seed", options->bench.seed, "Seed of every trial's random choices");
  command->add_option("--methods", options->methods,
                      "Comma-separated flow methods for Table II (default: all)");
  command
      ->add_option("--sweep-trials", options->bench.sweep_trials,
                   "Trials of the N and resolution sweeps (the first ones)")
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--depth-trials", options->bench.depth_trials,
                   "Trials per foreground depth of the Z_F sweep")
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--tracking-trials", options->bench.tracking_trials,
                   "Approaches of the tracking analysis")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--quick", options->quick,
                    "One trial per shape with the configured method, no sweeps (smoke test)");
  AddCommonOptions(command, &options->common);
  command->callback([options, exit_code] {
    output::OutputFolder out(options->common.out_dir);
    output::RunAndWriteSummary(out, [&] { RunBenchTs2p(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
