// aperture bench faults: a mission flown with one fault at a time, swept over the fault's levels,
// every flight counted as success, safe abort or crash (issue 18 item 5).
//
//   aperture bench faults --mission gap|led|... --out DIR [--trials 10] [--seed S] [--duration S]
//                         [--faults frame_drop,gust,...] [--levels sweep|acceptance]
//                         [--set KEY=V] [--threads T] [--shard K/N]
//
// Writes DIR/summary.json (baseline, faults: outcome counts per level, failures, acceptance; see
// experiments/faults/faults_bench.h), DIR/flights.csv (one row per flight) and DIR/report.html
// (success / safe abort / crash rate vs level per fault), or with --shard K/N the K-th block of
// the flights for `aperture bench merge`.
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "experiments/faults/faults_monte_carlo_bench.h"
#include "output/output_folder.h"

namespace aperture::apps {
namespace {

struct BenchFaultsOptions {
  std::string out_dir;
  bool overwrite = false;
  std::string levels = "sweep";
  MonteCarloCommandOptions monte_carlo;
  experiments::FaultsBenchOptions bench;
};

std::vector<std::string> FaultNames() {
  std::vector<std::string> names;
  for (const experiments::FaultSpec& fault : experiments::FaultCatalogue()) {
    names.push_back(fault.name);
  }
  return names;
}

}  // namespace

void AddBenchFaultsCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchFaultsOptions>();
  CLI::App* command = bench.add_subcommand(
      "faults",
      "A mission under one fault at a time (frame drops, latency, IMU noise and bias, gusts, a "
      "weak motor, a perception outage): success / safe abort / crash vs fault level");
  command
      ->add_option("--mission", options->bench.scenario,
                   "Scenario whose default mission is flown (as `aperture sim NAME`): " +
                       BuiltinScenarioList())
      ->required()
      ->check([](const std::string& name) {
        try {
          RequireBuiltinScenario(name);
          return std::string();
        } catch (const std::exception& e) {
          return std::string(e.what());
        }
      });
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  AddOverwriteFlag(command, &options->overwrite);
  command
      ->add_option("--trials", options->bench.repeats,
                   "Conditions per fault level (each flown at every level of every fault)")
      ->check(IntegerIn(1));
  AddSeedOption(command, &options->bench.seed, "Seed of the conditions");
  command->add_option("--duration", options->bench.duration_s, "Simulated time per flight [s]")
      ->check(FiniteNumberIn(0.0, kMaxDurationS, /*min_inclusive=*/false));
  command->add_option("--faults", options->bench.faults, "Faults swept (default all)")
      ->delimiter(',')
      ->check(CommaListOf(FaultNames()));
  command
      ->add_option("--levels", options->levels,
                   "sweep: 4 levels per fault up to the top of its range; acceptance: its default "
                   "level (the middle) and twice it")
      ->check(CLI::IsMember({"sweep", "acceptance"}));
  command->add_option("--set", options->bench.set_items,
                      "Scenario or mission override for every flight, e.g. mission.KEY=V");
  AddMonteCarloOptions(command, &options->monte_carlo);
  command->callback([options, exit_code] {
    options->bench.acceptance_levels = options->levels == "acceptance";
    output::OutputFolder out = OpenOutputFolder(options->out_dir, options->overwrite);
    output::RunAndWriteSummary(out, [&] {
      RunMonteCarloCommand(experiments::kFaultsBenchName,
                           experiments::FaultsBenchConfiguration(options->bench),
                           options->monte_carlo, out);
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
