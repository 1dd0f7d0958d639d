// aperture bench led: the infrared-LED tracker against rendered ground truth (issue 6).
//
//   aperture bench led --out DIR [--seed S] [--quick] [--only body_occlusion,merged]
//                      [--calibration-errors] [--threads T] [--shard K/N]
//
// Writes DIR/summary.json (sections accuracy, sweep, occlusion, merged, brute_force_timing,
// body_occlusion, timing, acceptance; see experiments/led/led_bench.h; --only runs the sections
// named), DIR/frames.csv (every tracked frame with its errors) and DIR/report.html (error plots,
// box plots per distance), or with --shard K/N the K-th block of the sections (a trial is a
// section, experiments/led/led_monte_carlo_bench.h) for `aperture bench merge`.
#include <memory>
#include <string>
#include <vector>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "experiments/led/led_monte_carlo_bench.h"
#include "output/output_folder.h"

namespace aperture::apps {
namespace {

struct BenchLedOptions {
  std::string out_dir;
  bool overwrite = false;
  std::uint64_t seed = 1;
  bool quick = false;
  std::vector<std::string> only;
  bool calibration_errors = false;
  MonteCarloCommandOptions monte_carlo;
};

}  // namespace

void AddBenchLedCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchLedOptions>();
  CLI::App* command = bench.add_subcommand(
      "led", "Infrared-LED pose tracking against rendered ground truth (thesis C.4 analogs)");
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  AddOverwriteFlag(command, &options->overwrite);
  AddSeedOption(command, &options->seed, "Seed of the random poses and sensor noise");
  command->add_flag("--quick", options->quick, "Fewer frames per section (same code paths)");
  command->add_option("--only", options->only, "Run only these sections (comma-separated keys)")
      ->delimiter(',')
      ->check(CLI::IsMember(experiments::LedBenchSectionKeys()));
  command->add_flag("--calibration-errors", options->calibration_errors,
                    "Render with the intrinsics and LED positions off by calibration-level "
                    "errors (focal +0.5 %, principal point (+1.5, -1) px, LEDs 1 mm) while the "
                    "tracker keeps the nominal ones");
  AddMonteCarloOptions(command, &options->monte_carlo);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->out_dir, options->overwrite);
    output::RunAndWriteSummary(out, [&] {
      experiments::LedBenchOptions bench;
      bench.seed = options->seed;
      bench.quick = options->quick;
      bench.only = options->only;
      bench.calibration_errors = options->calibration_errors;
      RunMonteCarloCommand(experiments::kLedBenchName, experiments::LedBenchConfiguration(bench),
                           options->monte_carlo, out);
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
