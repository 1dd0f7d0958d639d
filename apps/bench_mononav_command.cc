// aperture bench mononav: seeded SITL flights of the forest mission (issue 17; seed 003 Tables
// II and IV and the per-module timing).
//
//   aperture bench mononav --out DIR [--trials 40] [--seed S] [--duration S] [--quick]
//                          [--configurations edt,no_edt,random_waypoint]
//                          [--set forest.KEY=V] [--set mission.KEY=V]
//
// Writes DIR/summary.json (table_iv, table_ii, timing, acceptance; see
// experiments/mononav/mononav_bench.h), DIR/flights.csv (one row per flight) and DIR/report.html.
#include <memory>
#include <string>
#include <vector>

#include "apps/acceptance_outcome.h"
#include "apps/commands.h"
#include "experiments/mononav/mononav_bench.h"
#include "output/html_report.h"
#include "output/output_folder.h"

namespace aperture::apps {
namespace {

struct BenchMononavOptions {
  std::string out_dir;
  int trials = 40;
  long long seed = 1;
  double duration_s = 60.0;
  bool quick = false;
  std::vector<std::string> configurations;
  std::vector<std::string> set_items;
};

}  // namespace

void AddBenchMononavCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchMononavOptions>();
  CLI::App* command = bench.add_subcommand(
      "mononav", "Forest flights of the monocular-depth mission (seed 003 Tables II, IV, timing)");
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  command->add_option("--trials", options->trials, "Forest layouts (seeds --seed ..)")
      ->check(CLI::PositiveNumber);
  command->add_option("--seed", options->seed, "Seed of the first layout")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--duration", options->duration_s, "Simulated time per flight [s]")
      ->check(CLI::PositiveNumber);
  command->add_flag("--quick", options->quick,
                    "One short flight (4 m, one trunk on the line), EDT only (same code paths)");
  command
      ->add_option("--configurations", options->configurations,
                    "Configurations flown on every layout: edt,no_edt,random_waypoint (default "
                    "all; edt is always needed)")
      ->delimiter(',');
  command->add_option(
      "--set", options->set_items,
      "Scenario or mission override, e.g. forest.trees=30, mission.max_speed_mps=1");
  command->callback([options, exit_code] {
    output::OutputFolder out(options->out_dir);
    output::RunAndWriteSummary(out, [&] {
      out.summary()["command"] = "bench mononav";
      out.summary()["inputs"] = {{"trials", options->trials},
                                 {"seed", options->seed},
                                 {"duration_s", options->duration_s},
                                 {"quick", options->quick},
                                 {"configurations", options->configurations},
                                 {"set", options->set_items}};
      output::HtmlReport report("aperture bench mononav");
      experiments::MononavBenchOptions bench_options;
      bench_options.trials = options->trials;
      bench_options.first_seed = static_cast<std::uint64_t>(options->seed);
      bench_options.duration_s = options->duration_s;
      bench_options.quick = options->quick;
      bench_options.configurations = options->configurations;
      bench_options.set_items = options->set_items;
      bench_options.flights_csv_path = out.Path("flights.csv");
      experiments::RunMononavBench(bench_options, &out.summary(), &report);
      report.AddOutcome(AcceptanceOutcome(out.summary()["acceptance"]));
      report.AddRunDescription(out.summary(), out.ElapsedSeconds());
      report.AddCollapsedTable(out.summary(), "Every figure of summary.json");
      report.Write(out.Path("report.html"));
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
