// aperture bench control: the control-stack comparisons of issue 4 (thesis F.6/F.7, G.6, B.4
// analogs) on the simulated bench vehicle.
//
//   aperture bench control --out DIR [--seed S] [--quick] [--only drag,mixer]
//                          [--config FILE] [--set control.mixer=one_shot ...]
//                          [--threads T] [--shard K/N]
//
// The bench vehicle and its control stack come from the sections `control`, `dynamics`, `imu`,
// `range` and `vehicle` (sim/control_params_io.h, sim/sim_params_io.h; defaults: the thesis'
// vehicle analog, and a simulated vehicle that departs from the controllers' model:
// vehicle.mismatch, sim/sitl/vehicle_mismatch.h); every section's flights start from them and
// vary only what the section compares.
// Runs every section of experiments::ControlBenchSections() (or those named by --only) in order
// and writes DIR/summary.json (each section's figures under its key, plus timing.<key>_s) and
// DIR/report.html (each section's plots and tables), or with --shard K/N the K-th block of the
// sections (a trial is a section, experiments/control/control_monte_carlo_bench.h) for
// `aperture bench merge`.
#include <memory>
#include <nlohmann/json.hpp>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "experiments/control/control_monte_carlo_bench.h"
#include "output/output_folder.h"

namespace aperture::apps {
namespace {

struct BenchControlOptions {
  CommonOptions common;
  MonteCarloCommandOptions monte_carlo;
  experiments::ControlBenchOptions bench;
  std::vector<std::string> only;
};

}  // namespace

void AddBenchControlCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchControlOptions>();
  CLI::App* command = bench.add_subcommand(
      "control",
      "Control-stack comparisons: rotor drag, drag identification, body-rate law, "
      "mixer, saturation, throw recovery");
  AddCommonOptions(command, &options->common);
  AddSeedOption(command, &options->bench.seed, "Seed of every random stream");
  command->add_flag("--quick", options->bench.quick,
                    "Shorter flights and fewer trials (same code paths)");
  command->add_option("--only", options->only, "Run only these sections (comma-separated keys)")
      ->delimiter(',');
  AddMonteCarloOptions(command, &options->monte_carlo);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] {
      // Read here first so that a mistake is named by its file line or --set item.
      config::ConfigTree tree = LoadConfig(options->common, "");
      experiments::ControlBenchOptions bench = options->bench;
      experiments::ReadControlBenchVehicle(&tree, &bench);
      RunMonteCarloCommand(experiments::kControlBenchName,
                           experiments::ControlBenchConfiguration(
                               bench, options->only, nlohmann::json::parse(tree.ToJson())),
                           options->monte_carlo, out);
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
