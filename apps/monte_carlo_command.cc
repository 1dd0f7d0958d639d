#include "apps/monte_carlo_command.h"

#include <iostream>
#include <memory>

#include "apps/code_version.h"
#include "apps/command_support.h"
#include "experiments/bench/monte_carlo_run.h"
#include "output/interruption.h"
#include "output/progress_bar.h"
#include "servo/visp_tag_detector.h"

namespace aperture::apps {

experiments::MonteCarloBenchRegistry BenchRegistry() {
  perception::TagDetectorRegistry tag_detectors = perception::TagDetectorRegistry::WithBuiltins();
  tag_detectors.Register(servo::kVispTagDetectorName, &servo::CreateVispTagDetector);
  return experiments::MonteCarloBenchRegistry::WithBuiltins(tag_detectors);
}

void AddMonteCarloOptions(CLI::App* command, MonteCarloCommandOptions* options) {
  command
      ->add_option("--shard", options->shard,
                   "Run only shard K of N (K/N, 1 <= K <= N) of the trials and write them for "
                   "`aperture bench merge`")
      ->check([](const std::string& text) {
        try {
          experiments::ParseShardSpec(text);
          return std::string();
        } catch (const experiments::ShardSpecError& e) {
          return std::string(e.what());
        }
      });
  command->add_option("--threads", options->threads, "Trials flown concurrently (0 = all cores)")
      ->check(IntegerIn(0, 4096));
}

void RunMonteCarloCommand(const std::string& name, const nlohmann::json& configuration,
                          const MonteCarloCommandOptions& options, output::OutputFolder& out) {
  // Ctrl-C / SIGTERM: no further trial starts; the finished ones are written (monte_carlo_run.h).
  const output::InterruptionHandlers interruption;
  experiments::MonteCarloRunOptions run;
  if (!options.shard.empty()) run.shard = experiments::ParseShardSpec(options.shard);
  run.threads = options.threads;
  run.code_version = CodeVersion();
  std::unique_ptr<output::ProgressBar> progress;
  std::string outcome;
  try {
    outcome = experiments::RunMonteCarloBench(
        BenchRegistry(), name, configuration, run, out, [&](int done, int total) {
          if (!progress) {
            progress = std::make_unique<output::ProgressBar>(name + " trials",
                                                             static_cast<std::size_t>(total));
          }
          progress->Update(static_cast<std::size_t>(done));
        });
  } catch (const experiments::ShardSpecError& e) {
    throw CLI::ValidationError("--shard", e.what());  // a usage error: exit 2
  }
  if (progress) progress->Finish();
  std::cout << outcome << "\n";
}

}  // namespace aperture::apps
