// aperture bench led: the infrared-LED tracker against rendered ground truth (issue 6).
//
//   aperture bench led --out DIR [--seed S] [--quick] [--only body_occlusion,merged]
//
// Writes DIR/summary.json (sections accuracy, sweep, occlusion, merged, body_occlusion, timing,
// acceptance; see experiments/led/led_bench.h; --only runs the sections named), DIR/frames.csv
// (every tracked frame with its errors) and DIR/report.html (error plots, box plots per distance).
#include <memory>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "experiments/led/led_bench.h"
#include "output/acceptance_outcome.h"
#include "output/html_report.h"
#include "output/output_folder.h"

namespace aperture::apps {
namespace {

struct BenchLedOptions {
  std::string out_dir;
  long long seed = 1;
  bool quick = false;
  std::vector<std::string> only;
};

// Passed when every acceptance check (thesis C.4 analogs, experiments/led/led_bench.h) holds.
}  // namespace

void AddBenchLedCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchLedOptions>();
  CLI::App* command = bench.add_subcommand(
      "led", "Infrared-LED pose tracking against rendered ground truth (thesis C.4 analogs)");
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  command->add_option("--seed", options->seed, "Seed of the random poses and sensor noise")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--quick", options->quick, "Fewer frames per section (same code paths)");
  command->add_option("--only", options->only, "Run only these sections (comma-separated keys)")
      ->delimiter(',')
      ->check(CLI::IsMember(experiments::LedBenchSectionKeys()));
  command->callback([options, exit_code] {
    output::OutputFolder out(options->out_dir);
    output::RunAndWriteSummary(out, [&] {
      out.summary()["command"] = "bench led";
      out.summary()["inputs"] = {
          {"seed", options->seed}, {"quick", options->quick}, {"only", options->only}};
      output::HtmlReport report("aperture bench led");
      experiments::LedBenchOptions bench_options;
      bench_options.seed = static_cast<std::uint64_t>(options->seed);
      bench_options.quick = options->quick;
      bench_options.only = options->only;
      bench_options.frames_csv_path = out.Path("frames.csv");
      experiments::RunLedBench(bench_options, &out.summary(), &report);
      report.AddOutcome(output::AcceptanceOutcome(out.summary()["acceptance"]));
      report.AddRunDescription(out.summary(), out.ElapsedSeconds());
      report.AddCollapsedTable(out.summary(), "Every figure of summary.json");
      report.Write(out.Path("report.html"));
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
