// aperture bench control: the control-stack comparisons of issue 4 (thesis F.6/F.7, G.6, B.4
// analogs) on the simulated bench vehicle.
//
//   aperture bench control --out DIR [--seed S] [--quick] [--only drag,mixer]
//                          [--config FILE] [--set control.mixer=one_shot ...]
//
// The bench vehicle and its control stack come from the sections `control`, `dynamics`, `imu` and
// `range` (sim/control_params_io.h, sim/sim_params_io.h; defaults: the thesis' vehicle analog);
// every section's flights start from them and vary only what the section compares.
// Runs every section of experiments::ControlBenchSections() (or those named by --only) in order,
// printing one progress line per section, and writes DIR/summary.json (each section's figures
// under its key, plus timing.<key>_s) and DIR/report.html (each section's plots and tables).
#include <chrono>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "config/config_tree.h"
#include "experiments/control/control_bench_sections.h"
#include "output/html_report.h"
#include "output/output_folder.h"
#include "sim/control_params_io.h"
#include "sim/sim_params_io.h"

namespace aperture::apps {
namespace {

struct BenchControlOptions {
  CommonOptions common;
  experiments::ControlBenchOptions bench;
  std::vector<std::string> only;
};

std::vector<experiments::ControlBenchSection> SelectSections(const std::vector<std::string>& only) {
  std::vector<experiments::ControlBenchSection> all = experiments::ControlBenchSections();
  if (only.empty()) return all;
  std::vector<experiments::ControlBenchSection> selected;
  std::string known;
  for (const auto& section : all) known += (known.empty() ? "" : ", ") + section.key;
  for (const std::string& key : only) {
    bool found = false;
    for (const auto& section : all) {
      if (section.key == key) {
        selected.push_back(section);
        found = true;
      }
    }
    if (!found) {
      throw std::invalid_argument("--only: unknown section '" + key + "'; known: " + known);
    }
  }
  return selected;
}

void RunBenchControl(BenchControlOptions options, output::OutputFolder& out) {
  const std::vector<experiments::ControlBenchSection> sections = SelectSections(options.only);
  config::ConfigTree tree = LoadConfig(options.common, "");
  config::ParamReader root = tree.Reader();
  experiments::ControlBenchOptions& bench = options.bench;
  root.ReadSection("control", &bench.control);
  root.ReadSection("dynamics", &bench.dynamics);
  root.ReadSection("imu", &bench.imu);
  root.ReadSection("range", &bench.range);
  root.RejectUnknownKeys();
  nlohmann::json& summary = out.summary();
  summary["command"] = "bench control";
  nlohmann::json keys = nlohmann::json::array();
  for (const auto& section : sections) keys.push_back(section.key);
  summary["inputs"] = {{"seed", options.bench.seed},
                       {"quick", options.bench.quick},
                       {"recovery_trials", options.bench.recovery_trials},
                       {"sections", keys}};
  // The full effective vehicle and control stack (`--config OUT/summary.json` repeats them).
  tree.PutParams("control", bench.control);
  tree.PutParams("dynamics", bench.dynamics);
  tree.PutParams("imu", bench.imu);
  tree.PutParams("range", bench.range);
  summary["config"] = nlohmann::json::parse(tree.ToJson());
  output::HtmlReport report("aperture bench control");
  report.AddParagraph(
      "Control-stack comparisons of issue 4 on the simulated bench vehicle (rotor "
      "drag d_x = 0.5, d_y = 0.35 1/s, motor lag and kappa(f) of G.6.1, IMU "
      "noise), seed " +
      std::to_string(options.bench.seed) +
      (options.bench.quick ? ", quick mode (shorter flights, fewer trials)" : ""));
  for (size_t i = 0; i < sections.size(); ++i) {
    std::cerr << "bench control [" << i + 1 << "/" << sections.size() << "] " << sections[i].key
              << " ..." << std::flush;
    const auto start = std::chrono::steady_clock::now();
    sections[i].run(options.bench, &summary, &report);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary["timing"][sections[i].key + "_s"] = seconds;
    std::cerr << " done in " << seconds << " s\n";
  }
  // The sections compare controllers; their figures against the thesis are in each section.
  report.AddOutcome(
      {"done",
       std::to_string(sections.size()) + " section(s) of the control bench: " + keys.dump() + ".",
       {}});
  report.AddRunDescription(summary, out.ElapsedSeconds());
  report.AddCollapsedTable(summary, "Every figure of summary.json");
  report.Write(out.Path("report.html"));
  summary["outputs"] = {{"report", "report.html"}};
  std::cout << "aperture bench control: " << sections.size() << " section(s) written to "
            << out.directory() << "\n";
}

}  // namespace

void AddBenchControlCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchControlOptions>();
  CLI::App* command = bench.add_subcommand(
      "control",
      "Control-stack comparisons: rotor drag, drag identification, body-rate law, "
      "mixer, saturation, throw recovery");
  AddCommonOptions(command, &options->common);
  command->add_option("--seed", options->bench.seed, "Seed of every random stream");
  command->add_flag("--quick", options->bench.quick,
                    "Shorter flights and fewer trials (same code paths)");
  command->add_option("--only", options->only, "Run only these sections (comma-separated keys)")
      ->delimiter(',');
  command->callback([options, exit_code] {
    output::OutputFolder out(options->common.out_dir);
    output::RunAndWriteSummary(out, [&] { RunBenchControl(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
