// aperture bench: perception and control benchmarks against ground truth. Each benchmark is a
// subcommand in its own file (bench_<name>_command.cc) that parses its flags, runs the
// experiments of experiments/<name>/ and writes summary.json and report.html into --out.
#include "apps/commands.h"

namespace aperture::apps {

void AddBenchCommand(CLI::App& app, int* exit_code) {
  CLI::App* bench =
      app.add_subcommand("bench", "Run perception and control benchmarks against ground truth");
  bench->require_subcommand(1);
  AddBenchControlCommand(*bench, exit_code);
  AddBenchDeliveryCommand(*bench, exit_code);
  AddBenchFaultsCommand(*bench, exit_code);
  AddBenchGapCommand(*bench, exit_code);
  AddBenchGapflytCommand(*bench, exit_code);
  AddBenchLedCommand(*bench, exit_code);
  AddBenchMergeCommand(*bench, exit_code);
  AddBenchMononavCommand(*bench, exit_code);
  AddBenchSoakCommand(*bench, exit_code);
  AddBenchTs2pCommand(*bench, exit_code);
  AddBenchTagsCommand(*bench, exit_code);
}

}  // namespace aperture::apps
