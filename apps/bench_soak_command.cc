// aperture bench soak: the LED hover flown for a simulated hour in one process, watching memory
// and per-frame time (issue 18 item 6).
//
//   aperture bench soak --out DIR [--duration 3600] [--interval 10] [--seed S]
//                       [--set KEY=V ...]
//
// Writes DIR/soak.csv (per sample: simulated time, wall / CPU time, RSS, per-frame wall and CPU
// time median and max over the interval), DIR/summary.json (soak: RSS at minute 1 and at the end,
// growth, per-frame medians of the first and last ten minutes and their drift; buffers: the
// sizes of the records the flight keeps; acceptance: RSS growth < 5 %) and DIR/report.html; see
// experiments/soak/soak_bench.h. SIGINT/SIGTERM stop the flight and keep the samples so far.
#include <memory>
#include <string>
#include <vector>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "experiments/soak/soak_bench.h"
#include "output/interruption.h"
#include "output/number_format.h"
#include "output/output_folder.h"

namespace aperture::apps {
namespace {

struct BenchSoakOptions {
  std::string out_dir;
  bool overwrite = false;
  experiments::SoakBenchOptions bench;
};

}  // namespace

void AddBenchSoakCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchSoakOptions>();
  CLI::App* command = bench.add_subcommand(
      "soak", "The LED hover for a simulated hour: memory flat, no per-frame time drift");
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  AddOverwriteFlag(command, &options->overwrite);
  command
      ->add_option("--duration", options->bench.duration_s,
                   "Simulated time [s] (default 3600: RSS compared at minute 1 and the end)")
      ->check(FiniteNumberIn(0.0, kMaxDurationS, /*min_inclusive=*/false));
  command
      ->add_option("--interval", options->bench.interval_s,
                   "Simulated time between samples [s] (default 10; at most --duration)")
      ->check(FiniteNumberIn(0.0, kMaxDurationS, /*min_inclusive=*/false));
  AddSeedOption(command, &options->bench.seed, "Seed of the scenario and every sensor stream");
  command->add_option("--set", options->bench.set_items,
                      "Scenario or mission override as in `aperture sim led`, e.g. "
                      "cameras.ground.width=376");
  command->callback([options, exit_code] {
    if (options->bench.interval_s > options->bench.duration_s) {
      throw CLI::ValidationError("--interval", "the sampling interval (" +
                                                   output::FormatDouble(options->bench.interval_s) +
                                                   " s) is longer than --duration (" +
                                                   output::FormatDouble(options->bench.duration_s) +
                                                   " s); give a shorter interval");
    }
    output::OutputFolder out = OpenOutputFolder(options->out_dir, options->overwrite);
    const output::InterruptionHandlers interruption;
    output::RunAndWriteSummary(out, [&] { experiments::RunSoakBench(options->bench, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
