// aperture bench merge: the whole run's outputs from the shards of a Monte-Carlo bench.
//
//   aperture bench gap --trials 40 --shard 1/2 --out S1    (on one machine or Slurm task)
//   aperture bench gap --trials 40 --shard 2/2 --out S2    (on another)
//   aperture bench merge --out OUT S1 S2
//
// Writes OUT/summary.json, the per-trial files and report.html as the unsharded run would (the
// bench's own writer, experiments/bench/monte_carlo_run.h), plus cost.shards (threads, CPU and
// wall time, host per shard) and merged_from. Exit 1 when the shards do not merge (a shard that
// failed, different benches, code versions or configurations, overlapping or missing trials),
// 2 for usage errors (no shard folder, a folder that does not exist, OUT being a shard folder).
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/code_version.h"
#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "experiments/bench/monte_carlo_run.h"
#include "output/output_folder.h"

namespace aperture::apps {
namespace {

struct BenchMergeOptions {
  std::string out_dir;
  bool overwrite = false;
  std::vector<std::string> shard_dirs;
};

// OUT must not be one of the shards: opening it as an output folder would remove its summary.
void CheckOutIsNoShard(const BenchMergeOptions& options) {
  namespace fs = std::filesystem;
  for (const std::string& shard : options.shard_dirs) {
    std::error_code error;
    if (fs::exists(options.out_dir) && fs::equivalent(options.out_dir, shard, error)) {
      throw CLI::ValidationError("--out", options.out_dir +
                                              " is one of the shard folders; choose another "
                                              "output folder for the merge");
    }
  }
}

}  // namespace

void AddBenchMergeCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchMergeOptions>();
  CLI::App* command = bench.add_subcommand(
      "merge", "Merge the shard folders of a Monte-Carlo bench (--shard K/N runs) into one run");
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  AddOverwriteFlag(command, &options->overwrite);
  command->add_option("shards", options->shard_dirs, "The --out folders of the shards (any order)")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->callback([options, exit_code] {
    CheckOutIsNoShard(*options);
    output::OutputFolder out = OpenOutputFolder(options->out_dir, options->overwrite);
    output::RunAndWriteSummary(out, [&] {
      std::cout << experiments::MergeMonteCarloShards(BenchRegistry(), options->shard_dirs,
                                                      CodeVersion(), out)
                << "\n";
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
