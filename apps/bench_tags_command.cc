// aperture bench tags: the AprilTag front end and tag map against rendered ground truth
// (issue 15).
//
//   aperture bench tags --out DIR [--seed S] [--quick] [--section KEY]... [--threads T]
//                       [--shard K/N]
//
// Writes DIR/summary.json (sections detection, mapping, missions, acceptance; see
// experiments/tags/tag_bench.h), DIR/frames.csv (every detection-section frame per detector),
// DIR/observations.csv (every tag observation of the mapping pass) and DIR/report.html, or
// with --shard K/N the K-th block of the sections (a trial is a section,
// experiments/tags/tags_monte_carlo_bench.h) for `aperture bench merge`. The detectors: the
// built-in ones and ViSP's (BenchRegistry).
#include <memory>
#include <string>
#include <vector>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "experiments/tags/tag_bench.h"
#include "experiments/tags/tags_monte_carlo_bench.h"
#include "output/output_folder.h"
#include "servo/visp_tag_detector.h"

namespace aperture::apps {
namespace {

struct BenchTagsOptions {
  std::string out_dir;
  bool overwrite = false;
  std::uint64_t seed = 1;
  bool quick = false;
  std::vector<std::string> sections;
  MonteCarloCommandOptions monte_carlo;
};

}  // namespace

void AddBenchTagsCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchTagsOptions>();
  CLI::App* command = bench.add_subcommand(
      "tags", "AprilTag detection per detector and family, flips and the tag map (paper D)");
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  AddOverwriteFlag(command, &options->overwrite);
  AddSeedOption(command, &options->seed, "Seed of the views, noise and the tag field");
  command->add_flag("--quick", options->quick, "Fewer frames per section (same code paths)");
  command
      ->add_option("--section", options->sections,
                   "Run only this section (repeatable): detection, mapping, missions")
      ->check(CLI::IsMember(experiments::TagBenchSectionKeys()));
  AddMonteCarloOptions(command, &options->monte_carlo);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->out_dir, options->overwrite);
    output::RunAndWriteSummary(out, [&] {
      experiments::TagBenchOptions bench;
      bench.seed = options->seed;
      bench.quick = options->quick;
      bench.sections = options->sections;
      bench.detectors.Register(servo::kVispTagDetectorName, &servo::CreateVispTagDetector);
      RunMonteCarloCommand(experiments::kTagsBenchName, experiments::TagsBenchConfiguration(bench),
                           options->monte_carlo, out);
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
