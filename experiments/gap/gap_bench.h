#pragma once
// `aperture bench gap` (issue 5; seed 000 Sec. IV-B, Table I, Fig. 6 analogs): Monte-Carlo
// flights through the patterned gap in the SITL. Each trial draws its gap inclination, start
// pose, IMU noise/biases, frame drops and exposure (gap_trial_config.h), builds the `gap`
// scenario and the autopilot (gap_trial_autopilot.h), flies it, and evaluates success and the
// error at the gap on ground truth (gap_trial_evaluation.h).
//
//   GapBenchOptions options;  options.trials = 100;  options.seed = 1;
//   GapBenchResult result = RunGapBench(options, MakeGroundTruthGapAutopilotFactory());
//   WriteGapBenchOutputs(result, out);   // summary.json figures, trials.csv, report.html
//
// Trials run in parallel (oneTBB, `threads`); each owns its scenario, runner and autopilot and
// is a pure function of (seed, index), so results are identical for any thread count.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "control/quad_state.h"
#include "experiments/gap/gap_detector_sequence.h"
#include "experiments/gap/gap_trial_autopilot.h"
#include "experiments/gap/gap_trial_config.h"
#include "experiments/gap/gap_trial_evaluation.h"
#include "output/output_folder.h"
#include "sim/sitl/vehicle_mismatch.h"

namespace aperture::experiments {

struct GapBenchOptions {
  int trials = 100;
  std::uint64_t seed = 1;
  // Index of the first trial: trials first_trial .. first_trial + trials - 1 of the seed's
  // sequence, so a long run can be split into parts that fly exactly the trials of one run.
  int first_trial = 0;
  GapTrialRanges ranges;
  // Per trial, unless the autopilot reports done earlier [s]: the mission took 7-10.5 s in the
  // 100 trials of seed 1 (detection, hover, transfer, approach, traverse, recovery, 2 s position
  // hold), so the default leaves margin for slow recoveries.
  double duration_s = 15.0;
  int threads = 0;  // concurrent trials; 0 = oneTBB's default (all cores)
  HoverCriteria hover;
  // Overrides of the built-in `gap` scenario (sim/scenario), e.g. "cameras.front.supersampling=1",
  // and of the mission's parameters (section `mission`,
  // planning/gap_mission/gap_mission_params_io.h).
  std::vector<std::string> config_files;
  std::vector<std::string> set_items;
  // false: the SITL renders no camera (for ground-truth autopilots, which need none).
  bool render_cameras = true;
  // false: frames the mission would ignore (after the planned crossing) are not rendered
  // (SitlRunnerParams::render_ignored_frames; the same outcome, fewer renders).
  bool render_ignored_frames = false;
  // The detector section (gap_detector_sequence.h): rendered sequences flown past the gap, each
  // scored frame by frame; 0 = none. They run after the flights (in a Monte-Carlo run as the
  // trial indices first_trial + trials ..., so shards split them too).
  int detector_sequences = 0;
  GapDetectorSequenceRanges detector_ranges;
  // true: every trial is flown a second time with the paper's configuration of the mission
  // (PaperGapMissionParams), the same draws and seed, and both are reported (issue 21, item 4).
  bool paper_configuration = true;
  // vehicle.mismatch (sim/sitl/vehicle_mismatch.h; issue 21, item 1): each trial's simulated
  // vehicle departs from the controllers' model by a draw from the trial's seed within the
  // default VehicleMismatchBounds, with the hover thrust calibrated; false: vehicle = model.
  sim::VehicleMismatchParams vehicle{true, {}};
  // true: the paper's vehicle (830 g, 55 x 12 cm; paper_gap_vehicle.h) instead of the scenario's.
  bool paper_vehicle = false;
  // Throws std::invalid_argument naming the option (trials < 1, duration <= 0, threads < 0,
  // detector_sequences < 0, bad ranges).
  void Validate() const;
};

struct GapTrialRecord {
  GapTrialConfig config;
  std::string outcome;  // sim::ToString(SitlResult::Outcome), or "error" if the trial threw
  GapTrialEvaluation evaluation;
  std::optional<planning::TraverseTrajectory> plan;
  double traverse_start_time_s = 0.0;  // NaN: never started
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  std::string autopilot_name;    // perception::Autopilot::name()
  std::string autopilot_status;  // at the end of the run
  int frames_delivered = 0;
  int frames_dropped = 0;
  int frames_skipped = 0;  // not rendered: the mission would have ignored them
  // The SITL's CPU profile (experiments/bench/sitl_profile_json.h; null if the trial threw): a
  // measurement, exact when the trials run on one thread.
  nlohmann::json cpu_profile;
  // Fig. 6: the autopilot's estimate after every control step (when it had one, with a gap
  // estimate), in simulator coordinates relative to the gap (T_WG_true * T_MG_est^-1 * estimate
  // of the autopilot's frame M), and the ground truth at the same times.
  std::vector<control::QuadState> estimate_trace;
  std::vector<control::QuadState> truth_trace;
};

struct GapBenchResult {
  GapBenchOptions options;
  std::string autopilot_name;  // of the first trial that ran
  // The effective configuration (before per-trial changes): the base scenario, its SITL blocks
  // in full and the mission parameters (`mission`); `--config OUT/summary.json` repeats the run.
  nlohmann::json scenario_config;
  planning::GapMissionParams mission;  // GapTrialSetup::mission of every trial
  std::vector<GapTrialRecord> trials;  // in trial order
  // With options.paper_configuration: the same trials flown with PaperGapMissionParams(mission).
  std::vector<GapTrialRecord> paper_trials;
  std::vector<GapDetectorSequenceRecord> detector_sequences;  // in sequence order
};

// The options as summary.json "inputs" (all but `threads`, which does not change a result) and
// back: GapBenchOptionsFromJson(GapBenchOptionsToJson(o)) == o but for threads (0).
// std::invalid_argument naming a missing or malformed key.
nlohmann::json GapBenchOptionsToJson(const GapBenchOptions& options);
GapBenchOptions GapBenchOptionsFromJson(const nlohmann::json& json);

// Flies one trial. Exceptions of the autopilot or the simulator are caught and recorded as the
// failure reason ("error: ...") so that one broken trial does not end a long run.
GapTrialRecord RunGapTrial(const GapBenchOptions& options, const sim::ScenarioParams& base,
                           const planning::GapMissionParams& mission, const GapTrialConfig& trial,
                           const GapTrialAutopilotFactory& factory);

// What every trial of a run shares: the `gap` scenario with the overrides, the mission
// parameters, and the effective configuration (GapBenchResult::scenario_config).
struct GapBenchSetup {
  sim::ScenarioParams base;
  planning::GapMissionParams mission;
  planning::GapMissionParams paper_mission;  // PaperGapMissionParams(mission)
  nlohmann::json scenario_config;
};
// The paper's configuration of our mission (seed 000 Sec. II): no closed-loop lead-in before the
// open-loop traverse (lead_in_s = 0, the one stage beyond the paper); the rest is as `ours`.
planning::GapMissionParams PaperGapMissionParams(const planning::GapMissionParams& ours);

// Throws std::invalid_argument for invalid options or scenario overrides.
GapBenchSetup PrepareGapBench(const GapBenchOptions& options);

// All trials (each with our and, with options.paper_configuration, the paper's mission), then
// options.detector_sequences detector sequences; `on_trial_done(done_count)` is called
// (serialized) after each trial (both flights) or sequence finishes. Once SIGINT/SIGTERM asked to
// stop (output::InterruptionRequested()) nothing further starts and `trials` (and
// `detector_sequences`) hold the ones that finished, in index order.
// Throws std::invalid_argument for invalid options or scenario overrides.
GapBenchResult RunGapBench(const GapBenchOptions& options, const GapTrialAutopilotFactory& factory,
                           const std::function<void(int)>& on_trial_done = {});
// The same with `setup` = PrepareGapBench(options) done once (shards and benches reuse it).
GapBenchResult RunGapBench(const GapBenchOptions& options, const GapBenchSetup& setup,
                           const GapTrialAutopilotFactory& factory,
                           const std::function<void(int)>& on_trial_done = {});

// Detector sequence `index` of a run: DrawGapDetectorSequence from the options' detector ranges
// and seed, rendered in the setup's scenario and scored with the mission's detector parameters.
GapDetectorSequenceRecord RunGapBenchDetectorSequence(const GapBenchOptions& options,
                                                      const GapBenchSetup& setup, int index);

// The figures of summary.json: trials, successes, success_rate, error_at_gap (per axis:
// position_mean/_std [m], velocity_mean/_std [m/s], orientation_mean_deg/_std_deg [roll, pitch]
// as mean and std of |error| like Table I, plus signed means, norms and the arrival-time error,
// over every trial that crossed the gap plane with a plan, successful or not, like the paper),
// failure reasons, success by inclination bins and the per-trial list "per_trial"; with detector
// sequences, "detector" (gap_detector_summary.h). "table_i" holds Table I by the paper's
// definitions (gap_trial_evaluation.h: the full state at the planned t_c, mean and std of |error|
// per axis over every trial with a plan, success with the footprint check) for "ours" and, when
// flown, "paper" (with its failures and per-trial list under "paper_configuration").
nlohmann::json SummarizeGapBench(const GapBenchResult& result);

// summary.json fields (SummarizeGapBench + inputs), trials.csv (one row per trial; with the paper
// configuration also paper_trials.csv),
// detector_frames.csv (with detector sequences: one row per rendered frame) and report.html
// (success by inclination, error histograms, Fig. 6 analogs for up to three trials nearest to
// the paper's 20/0, 45/0 and 30/30 deg roll/pitch gaps, the detector section).
void WriteGapBenchOutputs(const GapBenchResult& result, output::OutputFolder& out);

}  // namespace aperture::experiments
