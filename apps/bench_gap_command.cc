// aperture bench gap: Monte-Carlo flights through the inclined patterned gap (issue 5; seed 000
// Sec. IV-B: success rate, Table I errors at the gap, Fig. 6 estimate vs ground truth).
//
//   aperture bench gap [--trials N] [--seed S] [--first-trial K]
//                      [--max-roll-deg R] [--max-pitch-deg P]
//                      [--max-drop-probability D] [--motion-blur-subframes K]
//                      [--autopilot mission|ground_truth] [--duration S] [--threads T]
//                      [--render-ignored-frames] [--detector-sequences N]
//                      [--no-paper-configuration] [--vehicle-mismatch on|off]
//                      [--vehicle ours|paper]
//                      [--shard K/N] [--config FILE] [--set key=value ...] --out DIR
//
// --config/--set override the built-in `gap` scenario (e.g. --set cameras.front.supersampling=1)
// and the mission's parameters (--set mission.hover_s=1, section `mission`); summary.json "config"
// holds the full effective configuration, which `--config OUT/summary.json` flies again.
// Every trial is flown with our mission and again with the paper's configuration (no lead-in)
// unless --no-paper-configuration; summary.json "table_i" reports Table I by the paper's
// definitions for both. Writes DIR/summary.json (success_rate, table_i, error_at_gap.*,
// per_trial), DIR/trials.csv (and paper_trials.csv) and DIR/report.html
// (experiments/gap/gap_bench.h); --detector-sequences adds the detector on rendered sequences flown
// past the gap (summary.json "detector", DIR/detector_frames.csv, a report section;
// experiments/gap/gap_detector_sequence.h), or with --shard K/N the K-th block of the trials and
// sequences for `aperture bench merge` (experiments/bench/monte_carlo_run.h).
#include <memory>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/monte_carlo_command.h"
#include "config/usage_error.h"
#include "experiments/gap/gap_monte_carlo_bench.h"
#include "output/number_format.h"

namespace aperture::apps {
namespace {

struct BenchGapOptions {
  CommonOptions common;
  MonteCarloCommandOptions monte_carlo;
  experiments::GapBenchOptions bench;
  std::string autopilot = "mission";
  bool no_paper_configuration = false;
  std::string vehicle_mismatch = "on";
  std::string vehicle = "ours";
};

}  // namespace

void AddBenchGapCommand(CLI::App& bench, int* exit_code) {
  auto options = std::make_shared<BenchGapOptions>();
  CLI::App* command = bench.add_subcommand(
      "gap", "Monte-Carlo flights through the inclined patterned gap (seed 000 Table I, Fig. 6)");
  command->add_option("--trials", options->bench.trials, "Number of trials")->check(IntegerIn(1));
  AddSeedOption(command, &options->bench.seed, "Seed of every trial's random choices");
  command
      ->add_option("--first-trial", options->bench.first_trial,
                   "Index of the first trial (a part of a longer run of the same seed)")
      ->check(IntegerIn(0));
  command
      ->add_option("--min-roll-deg", options->bench.ranges.min_roll_deg,
                   "Gap roll drawn uniformly from [min, max] deg (e.g. 45 with --max-roll-deg 60 "
                   "for the steep range alone)")
      ->check(FiniteNumberIn(0.0, 89.0));
  command
      ->add_option("--max-roll-deg", options->bench.ranges.max_roll_deg,
                   "Gap roll drawn uniformly from [min, max] deg")
      ->check(FiniteNumberIn(0.0, 89.0));
  command
      ->add_option("--max-pitch-deg", options->bench.ranges.max_pitch_deg,
                   "Gap pitch drawn uniformly from [0, max] deg")
      ->check(FiniteNumberIn(0.0, 89.0));
  command
      ->add_option("--max-drop-probability", options->bench.ranges.max_drop_probability,
                   "Camera frame-drop probability drawn uniformly from [0, max]")
      ->check(FiniteNumberIn(0.0, 0.99));
  command
      ->add_option("--motion-blur-subframes", options->bench.ranges.motion_blur_subframes,
                   "Renders averaged per frame over the random exposure (1 = no blur; each "
                   "one costs a full render)")
      ->check(IntegerIn(1, 64));
  command->add_flag("--render-ignored-frames", options->bench.render_ignored_frames,
                    "Also render the frames the mission ignores (after the planned crossing); "
                    "the same outcome at a higher cost");
  command
      ->add_option("--detector-sequences", options->bench.detector_sequences,
                   "Rendered sequences flown past the gap (roll to 60 deg, 1-6 m, to 3 m/s) on "
                   "which the gap detector is scored frame by frame after the flights (0 = none)")
      ->check(IntegerIn(0));
  command->add_flag("--no-paper-configuration", options->no_paper_configuration,
                    "Fly only our configuration; by default every trial is flown again with the "
                    "paper's (mission.lead_in_s=0) and both are reported (summary.json table_i)");
  command
      ->add_option("--vehicle-mismatch", options->vehicle_mismatch,
                   "on: each trial's simulated vehicle departs from the controllers' model "
                   "(drag, rotors, latencies; sim/sitl/vehicle_mismatch.h); off: vehicle = model")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  command
      ->add_option("--vehicle", options->vehicle,
                   "ours: the scenario's vehicle (0.45 kg, 48 x 16 cm); paper: seed 000's (830 g, "
                   "55 x 12 cm between propeller tips; experiments/gap/paper_gap_vehicle.h)")
      ->check(CLI::IsMember({"ours", "paper"}))
      ->capture_default_str();
  command->add_option("--duration", options->bench.duration_s, "Simulated time per trial [s]")
      ->check(FiniteNumberIn(0.0, kMaxDurationS, /*min_inclusive=*/false));
  command
      ->add_option("--autopilot", options->autopilot,
                   "mission: the vision gap mission (camera + IMU); ground_truth: the same "
                   "traverse flown on ground truth without cameras (control-only reference)")
      ->check(CLI::IsMember({"mission", "ground_truth"}));
  AddCommonOptions(command, &options->common);
  AddMonteCarloOptions(command, &options->monte_carlo);
  command->callback([options, exit_code] {
    const experiments::GapTrialRanges& ranges = options->bench.ranges;
    if (ranges.min_roll_deg > ranges.max_roll_deg) {
      throw config::UsageError("--min-roll-deg " + output::FormatDouble(ranges.min_roll_deg) +
                               " is above --max-roll-deg " +
                               output::FormatDouble(ranges.max_roll_deg) +
                               " (the default maximum is 45): raise --max-roll-deg");
    }
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] {
      experiments::GapBenchOptions bench = options->bench;
      bench.paper_configuration = !options->no_paper_configuration;
      bench.vehicle.mismatch = options->vehicle_mismatch == "on";
      bench.paper_vehicle = options->vehicle == "paper";
      bench.config_files = options->common.config_files;
      bench.set_items = options->common.set_items;
      RunMonteCarloCommand(experiments::kGapBenchName,
                           experiments::GapBenchConfiguration(bench, options->autopilot),
                           options->monte_carlo, out);
    });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
