// aperture bench tags: the AprilTag front end and tag map against rendered ground truth
// (issue 15).
//
//   aperture bench tags --out DIR [--seed S] [--quick]
//
// Writes DIR/summary.json (sections detection, mapping, acceptance; see
// experiments/tags/tag_bench.h), DIR/frames.csv (every detection-section frame per detector),
// DIR/observations.csv (every tag observation of the mapping pass) and DIR/report.html.
#include <memory>
#include <string>

#include "apps/commands.h"
#include "experiments/tags/tag_bench.h"
#include "output/html_report.h"
#include "output/output_folder.h"
#include "servo/visp_tag_detector.h"

namespace aperture::apps {
namespace {

struct BenchTagsOptions {
  std::string out_dir;
  long long seed = 1;
  bool quick = false;
};

}  // namespace

void AddBenchTagsCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchTagsOptions>();
  CLI::App* command = bench.add_subcommand(
      "tags", "AprilTag detection per detector and family, flips and the tag map (paper D)");
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  command->add_option("--seed", options->seed, "Seed of the views, noise and the tag field")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--quick", options->quick, "Fewer frames per section (same code paths)");
  command->callback([options, exit_code] {
    output::OutputFolder out(options->out_dir);
    output::RunAndWriteSummary(out, [&] {
      out.summary()["command"] = "bench tags";
      out.summary()["inputs"] = {{"seed", options->seed}, {"quick", options->quick}};
      output::HtmlReport report("aperture bench tags");
      experiments::TagBenchOptions bench_options;
      bench_options.seed = static_cast<std::uint64_t>(options->seed);
      bench_options.quick = options->quick;
      bench_options.detectors.Register(servo::kVispTagDetectorName, &servo::CreateVispTagDetector);
      bench_options.frames_csv_path = out.Path("frames.csv");
      bench_options.observations_csv_path = out.Path("observations.csv");
      experiments::RunTagBench(bench_options, &out.summary(), &report);
      report.Write(out.Path("report.html"));
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
