#include "experiments/gap/gap_bench.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>

#include "control/constants.h"
#include "experiments/bench/monte_carlo_bench.h"
#include "experiments/bench/sitl_profile_json.h"
#include "experiments/gap/gap_detector_summary.h"
#include "experiments/gap/gap_mission_factory.h"
#include "experiments/gap/gap_trial_record_json.h"
#include "experiments/gap/paper_gap_vehicle.h"
#include "output/interruption.h"
#include "output/json_eigen.h"
#include "planning/gap_mission/gap_mission_params_io.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_sitl.h"

namespace aperture::experiments {
namespace {

using control::kNaN;

// Forwards everything to the trial's autopilot and records its estimate after every Step, mapped
// from the autopilot's world frame into the simulator's through the gap: T_WG_true * T_MG_est^-1
// (the estimate relative to the estimated gap, placed at the true gap), as the errors at the gap
// are defined (gap_trial_evaluation.h).
class RecordingAutopilot : public perception::Autopilot {
 public:
  RecordingAutopilot(GapTrialAutopilot* trial, const Eigen::Isometry3d& T_WG_true)
      : trial_(trial), inner_(trial->autopilot()), T_WG_true_(T_WG_true) {}
  std::string name() const override { return inner_.name(); }
  void OnImu(const perception::ImuSample& sample) override { inner_.OnImu(sample); }
  void OnFrame(const perception::Frame& frame) override { inner_.OnFrame(frame); }
  bool WantsFrame(int camera_id, double t_s) const override {
    return inner_.WantsFrame(camera_id, t_s);
  }
  void OnRange(const perception::RangeReading& reading) override { inner_.OnRange(reading); }
  bool UsesGroundTruth() const override { return inner_.UsesGroundTruth(); }
  void OnGroundTruth(const control::QuadState& state) override { inner_.OnGroundTruth(state); }
  perception::AutopilotCommand Step(double t_s) override {
    const perception::AutopilotCommand command = inner_.Step(t_s);
    const std::optional<control::QuadState> estimate = trial_->estimate();
    const std::optional<planning::GapPose> gap = trial_->gap_estimate();
    if (estimate && gap) {
      Eigen::Isometry3d T_MG = Eigen::Isometry3d::Identity();
      T_MG.linear() = gap->R_WG;
      T_MG.translation() = gap->p_WG;
      const Eigen::Isometry3d T_WM = T_WG_true_ * T_MG.inverse();
      control::QuadState mapped = *estimate;
      mapped.t_s = t_s;
      mapped.p_WB = T_WM * estimate->p_WB;
      mapped.v_W = T_WM.linear() * estimate->v_W;
      mapped.q_WB = Eigen::Quaterniond(T_WM.linear()) * estimate->q_WB;
      estimates_.push_back(mapped);
    }
    return command;
  }
  std::string status() const override { return inner_.status(); }
  std::vector<control::QuadState>& estimates() { return estimates_; }

 private:
  GapTrialAutopilot* trial_;
  perception::Autopilot& inner_;
  Eigen::Isometry3d T_WG_true_;
  std::vector<control::QuadState> estimates_;
};

// Ground truth at each of `times` (the latest recorded state at or before it).
std::vector<control::QuadState> SampleTruth(const std::vector<control::QuadState>& trajectory,
                                            const std::vector<control::QuadState>& at) {
  std::vector<control::QuadState> truth;
  truth.reserve(at.size());
  for (const control::QuadState& sample : at) {
    auto it =
        std::upper_bound(trajectory.begin(), trajectory.end(), sample.t_s + 1e-9,
                         [](double t, const control::QuadState& state) { return t < state.t_s; });
    if (it == trajectory.begin()) continue;
    truth.push_back(*std::prev(it));
  }
  return truth;
}

struct AxisStatistics {
  Eigen::VectorXd abs_mean, abs_std, signed_mean, signed_std;
};

AxisStatistics ComputeAxisStatistics(const std::vector<Eigen::VectorXd>& errors, int axes) {
  AxisStatistics stats{Eigen::VectorXd::Constant(axes, kNaN), Eigen::VectorXd::Constant(axes, kNaN),
                       Eigen::VectorXd::Constant(axes, kNaN),
                       Eigen::VectorXd::Constant(axes, kNaN)};
  const double n = static_cast<double>(errors.size());
  if (errors.empty()) return stats;
  for (int a = 0; a < axes; ++a) {
    double sum_abs = 0.0, sum = 0.0;
    for (const Eigen::VectorXd& e : errors) {
      sum_abs += std::abs(e(a));
      sum += e(a);
    }
    stats.abs_mean(a) = sum_abs / n;
    stats.signed_mean(a) = sum / n;
    double ss_abs = 0.0, ss = 0.0;
    for (const Eigen::VectorXd& e : errors) {
      ss_abs += std::pow(std::abs(e(a)) - stats.abs_mean(a), 2);
      ss += std::pow(e(a) - stats.signed_mean(a), 2);
    }
    // Sample standard deviation (n - 1), as for the paper's 35 flights; 0 for a single trial.
    const double dof = std::max(1.0, n - 1.0);
    stats.abs_std(a) = std::sqrt(ss_abs / dof);
    stats.signed_std(a) = std::sqrt(ss / dof);
  }
  return stats;
}

nlohmann::json MeanStd(const std::vector<double>& values) {
  if (values.empty()) return {{"mean", kNaN}, {"std", kNaN}};
  double sum = 0.0;
  for (double v : values) sum += v;
  const double mean = sum / values.size();
  double ss = 0.0;
  for (double v : values) ss += (v - mean) * (v - mean);
  return {{"mean", mean}, {"std", std::sqrt(ss / std::max<double>(1.0, values.size() - 1.0))}};
}

// The statistics of a set of errors at the gap: mean and std of |error| per axis (Table I) and of
// the signed error, of the norms, and of the arrival time (over the finite ones).
nlohmann::json ErrorFigures(const std::vector<GapStateError>& errors) {
  std::vector<Eigen::VectorXd> position, velocity, orientation;
  std::vector<double> position_norm, velocity_norm, time_error;
  for (const GapStateError& e : errors) {
    position.push_back(e.position_m);
    velocity.push_back(e.velocity_mps);
    orientation.push_back(e.orientation_deg);
    position_norm.push_back(e.position_m.norm());
    velocity_norm.push_back(e.velocity_mps.norm());
    if (std::isfinite(e.time_s)) time_error.push_back(e.time_s);
  }
  const AxisStatistics p = ComputeAxisStatistics(position, 3);
  const AxisStatistics v = ComputeAxisStatistics(velocity, 3);
  const AxisStatistics o = ComputeAxisStatistics(orientation, 2);
  return {
      {"trials", static_cast<int>(errors.size())},
      {"position_mean", output::EigenToJson(p.abs_mean)},
      {"position_std", output::EigenToJson(p.abs_std)},
      {"position_signed_mean", output::EigenToJson(p.signed_mean)},
      {"position_signed_std", output::EigenToJson(p.signed_std)},
      {"velocity_mean", output::EigenToJson(v.abs_mean)},
      {"velocity_std", output::EigenToJson(v.abs_std)},
      {"velocity_signed_mean", output::EigenToJson(v.signed_mean)},
      {"velocity_signed_std", output::EigenToJson(v.signed_std)},
      {"orientation_mean_deg", output::EigenToJson(o.abs_mean)},
      {"orientation_std_deg", output::EigenToJson(o.abs_std)},
      {"orientation_signed_mean_deg", output::EigenToJson(o.signed_mean)},
      {"orientation_signed_std_deg", output::EigenToJson(o.signed_std)},
      {"position_norm_m", MeanStd(position_norm)},
      {"velocity_norm_mps", MeanStd(velocity_norm)},
      {"arrival_time_error_s", MeanStd(time_error)},
  };
}

// Failure reasons grouped by their text before the first digit-bearing detail.
std::map<std::string, int> CountFailures(const std::vector<GapTrialRecord>& trials) {
  std::map<std::string, int> failures;
  for (const GapTrialRecord& record : trials) {
    if (record.evaluation.success) continue;
    const std::string& reason = record.evaluation.failure_reason;
    const std::size_t cut = reason.find_first_of(":0123456789");
    failures[reason.substr(0, cut == std::string::npos ? reason.size() : cut)]++;
  }
  return failures;
}

// Table I by the paper's definitions (SummarizeGapBench's "table_i") over `trials`.
nlohmann::json TableIFigures(const std::vector<GapTrialRecord>& trials) {
  std::vector<GapStateError> errors;
  int successes = 0;
  for (const GapTrialRecord& record : trials) {
    if (record.evaluation.success) ++successes;
    const std::optional<GapStateError>& error = record.evaluation.error_at_planned_tc;
    if (error) errors.push_back(*error);
  }
  const int n = static_cast<int>(trials.size());
  nlohmann::json figures = ErrorFigures(errors);
  figures["trials"] = n;  // all of them; the errors cover trials_with_plan
  figures["trials_with_plan"] = static_cast<int>(errors.size());
  figures["trials_without_plan"] = n - static_cast<int>(errors.size());
  figures["successes"] = successes;
  figures["success_rate"] = n > 0 ? static_cast<double>(successes) / n : kNaN;
  figures["failures"] = CountFailures(trials);
  return figures;
}

// The mission parameters every trial flies: the base scenario's camera and pattern sizes and the
// nominal IMU of its SITL configuration (GapMissionParamsFor; the trials change none of these),
// then the `mission` section.
planning::GapMissionParams BaseMissionParams(const sim::ScenarioParams& base,
                                             config::ParamReader& mission_config) {
  const sim::Scenario scenario = sim::BuildScenario(base);
  sim::SitlRunnerParams sitl;
  sim::ConfigureSitlFromScenario(scenario, &sitl);
  planning::GapMissionParams mission = GapMissionParamsFor(scenario, sitl.imu);
  LoadParams(mission_config, &mission);
  return mission;
}

}  // namespace

void GapBenchOptions::Validate() const {
  if (trials < 1) {
    throw std::invalid_argument("--trials " + std::to_string(trials) + ": must be >= 1");
  }
  if (!(std::isfinite(duration_s) && duration_s > 0.0)) {
    throw std::invalid_argument("--duration " + std::to_string(duration_s) + ": must be > 0 s");
  }
  if (first_trial < 0) {
    throw std::invalid_argument("--first-trial " + std::to_string(first_trial) + ": must be >= 0");
  }
  if (threads < 0) {
    throw std::invalid_argument("--threads " + std::to_string(threads) +
                                ": must be >= 0 (0 = all cores)");
  }
  if (detector_sequences < 0) {
    throw std::invalid_argument("--detector-sequences " + std::to_string(detector_sequences) +
                                ": must be >= 0 (0 = no detector section)");
  }
  ranges.Validate();
  detector_ranges.Validate();
  vehicle.Validate();
}

GapTrialRecord RunGapTrial(const GapBenchOptions& options, const sim::ScenarioParams& base,
                           const planning::GapMissionParams& mission, const GapTrialConfig& trial,
                           const GapTrialAutopilotFactory& factory) {
  const auto wall_start = std::chrono::steady_clock::now();
  GapTrialRecord record;
  record.config = trial;
  record.traverse_start_time_s = kNaN;
  try {
    sim::ScenarioParams scenario_params = base;
    ApplyGapTrial(trial, &scenario_params);
    sim::Scenario scenario = sim::BuildScenario(scenario_params);
    sim::SitlRunnerParams params;
    params.duration_s = options.duration_s;
    params.trajectory_decimation = 1;  // 1 kHz ground truth: the crossing within ~3 mm
    sim::ConfigureSitlFromScenario(scenario, &params);
    if (!options.render_cameras) params.cameras.clear();
    for (sim::SitlCamera& camera : params.cameras) camera.render.ground_truth = false;
    params.render_ignored_frames = options.render_ignored_frames;
    const sim::ImuSensorParams nominal_imu = params.imu;
    const control::VehicleParameters nominal_vehicle = params.dynamics.vehicle;
    ApplyGapTrial(trial, &params);
    sim::ApplyVehicleMismatch(options.vehicle, trial.seed, &params);
    const GapGeometry gap = GapGeometryOf(scenario);

    GapTrialSetup setup;
    setup.scenario = &scenario;
    setup.vehicle = nominal_vehicle;  // the controllers' model, also with a mismatched vehicle
    setup.initial_state = params.initial_state;
    setup.control_rate_hz = params.control_rate_hz;
    setup.imu = nominal_imu;
    setup.mission = mission;
    const std::unique_ptr<GapTrialAutopilot> autopilot = factory(setup);
    RecordingAutopilot recorder(autopilot.get(), gap.T_WG);
    sim::SitlRunner runner(params, &scenario.scene());
    const sim::SitlResult result = runner.Run(recorder, sim::MakeScenarioHooks(&scenario));

    record.plan = autopilot->traverse_plan();
    record.traverse_start_time_s = autopilot->traverse_start_time_s();
    record.evaluation =
        EvaluateGapTrial(result, gap, VehicleFootprintOf(params.dynamics.vehicle, params.collision),
                         record.plan, record.traverse_start_time_s, options.hover);
    record.outcome = sim::ToString(result.outcome);
    record.sim_time_s = result.sim_time_s;
    record.cpu_profile = SitlCpuProfileToJson(result.timing.cpu, result.sim_time_s);
    record.autopilot_name = result.autopilot_name;
    record.autopilot_status = result.autopilot_status;
    for (const sim::SitlCameraStats& camera : result.cameras) {
      record.frames_delivered += camera.frames_delivered;
      record.frames_dropped += camera.frames_dropped;
      record.frames_skipped += camera.frames_skipped;
    }
    record.estimate_trace = std::move(recorder.estimates());
    record.truth_trace = SampleTruth(result.trajectory, record.estimate_trace);
  } catch (const std::exception& error) {
    record.outcome = "error";
    record.evaluation = GapTrialEvaluation{};
    record.evaluation.failure_reason = std::string("error: ") + error.what();
  }
  record.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return record;
}

planning::GapMissionParams PaperGapMissionParams(const planning::GapMissionParams& ours) {
  planning::GapMissionParams paper = ours;
  paper.lead_in_s = 0.0;
  return paper;
}

GapBenchSetup PrepareGapBench(const GapBenchOptions& options) {
  options.Validate();
  config::ConfigTree tree = sim::ScenarioConfig("gap", options.config_files, options.set_items);
  config::ParamReader root = tree.Reader();
  GapBenchSetup setup;
  LoadParams(root, &setup.base);
  if (options.paper_vehicle) UsePaperGapVehicle(&setup.base);
  config::ParamReader mission_config = root.Section("mission");
  root.RejectUnknownKeys();
  if (setup.base.scenario != "gap") {
    throw std::invalid_argument("aperture bench gap: the scenario overrides set scenario: " +
                                setup.base.scenario + "; only the gap scenario can be benchmarked");
  }
  setup.mission = BaseMissionParams(setup.base, mission_config);
  setup.paper_mission = PaperGapMissionParams(setup.mission);
  sim::PutEffectiveSitlBlocks(setup.base, &tree);
  tree.PutParams("mission", setup.mission);
  setup.scenario_config = nlohmann::json::parse(tree.ToJson());
  return setup;
}

GapBenchResult RunGapBench(const GapBenchOptions& options, const GapTrialAutopilotFactory& factory,
                           const std::function<void(int)>& on_trial_done) {
  return RunGapBench(options, PrepareGapBench(options), factory, on_trial_done);
}

GapBenchResult RunGapBench(const GapBenchOptions& options, const GapBenchSetup& setup,
                           const GapTrialAutopilotFactory& factory,
                           const std::function<void(int)>& on_trial_done) {
  options.Validate();
  const sim::ScenarioParams& base = setup.base;
  GapBenchResult result;
  result.options = options;
  result.mission = setup.mission;
  result.scenario_config = setup.scenario_config;
  std::vector<GapTrialConfig> configs;
  for (int i = 0; i < options.trials; ++i) {
    configs.push_back(DrawGapTrial(options.ranges, options.seed, options.first_trial + i,
                                   base.vehicle_start.p_m));
  }
  result.trials.resize(configs.size());
  if (options.paper_configuration) result.paper_trials.resize(configs.size());
  std::vector<char> flown(configs.size(), 0);
  std::mutex mutex;
  int done = 0;
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(0, options.trials, [&](int i) {
      if (output::InterruptionRequested()) return;  // Ctrl-C: start no further trial
      result.trials[i] = RunGapTrial(options, base, result.mission, configs[i], factory);
      if (options.paper_configuration) {
        result.paper_trials[i] =
            RunGapTrial(options, base, setup.paper_mission, configs[i], factory);
      }
      flown[i] = 1;
      const std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (on_trial_done) on_trial_done(done);
    });
  });
  if (done < options.trials) {  // interrupted: keep the trials that were flown, in index order
    const auto keep_flown = [&flown](std::vector<GapTrialRecord>* records) {
      std::vector<GapTrialRecord> kept;
      for (std::size_t i = 0; i < records->size(); ++i) {
        if (flown[i]) kept.push_back(std::move((*records)[i]));
      }
      *records = std::move(kept);
    };
    keep_flown(&result.trials);
    keep_flown(&result.paper_trials);
  }
  for (const GapTrialRecord& record : result.trials) {
    if (result.autopilot_name.empty()) result.autopilot_name = record.autopilot_name;
  }
  if (done < options.trials || options.detector_sequences == 0) return result;
  const std::vector<nlohmann::json> sequences = RunTrialsInParallel(
      {0, options.detector_sequences}, options.threads,
      [&](int sequences_done) {
        if (on_trial_done) on_trial_done(done + sequences_done);
      },
      [&](int k) {
        return GapDetectorSequenceRecordToJson(RunGapBenchDetectorSequence(options, setup, k));
      });
  for (const nlohmann::json& record : sequences) {
    result.detector_sequences.push_back(GapDetectorSequenceRecordFromJson(record));
  }
  return result;
}

GapDetectorSequenceRecord RunGapBenchDetectorSequence(const GapBenchOptions& options,
                                                      const GapBenchSetup& setup, int index) {
  return RunGapDetectorSequence(
      DrawGapDetectorSequence(options.detector_ranges, options.seed, index), setup.base,
      setup.mission.detector);
}

nlohmann::json SummarizeGapBench(const GapBenchResult& result) {
  nlohmann::json summary;
  const int trials = static_cast<int>(result.trials.size());
  int successes = 0;
  std::vector<GapStateError> errors_at_crossing;
  nlohmann::json per_trial = nlohmann::json::array();
  for (const GapTrialRecord& record : result.trials) {
    if (record.evaluation.success) ++successes;
    if (record.evaluation.error) errors_at_crossing.push_back(*record.evaluation.error);
    per_trial.push_back(GapTrialSummaryJson(record));
  }
  summary["trials"] = trials;
  summary["successes"] = successes;
  summary["success_rate"] = trials > 0 ? static_cast<double>(successes) / trials : kNaN;
  summary["error_at_gap"] = ErrorFigures(errors_at_crossing);
  summary["error_at_gap"]["definition"] =
      "at the crossing (ground truth crossing the gap plane): actual (ground truth relative to "
      "the true gap) minus desired (traverse plan at its t_c relative to the plan's gap "
      "estimate), world axes; *_mean/*_std = mean/std of |error| per axis, *_signed_* of the "
      "signed error; every trial that crossed with a plan, successful or not. The along-track "
      "and timing error are removed (see table_i for the paper's definition)";
  summary["table_i"] = {
      {"definition",
       "seed 000 Table I: the ground truth at the planned t_c (traverse start + plan t_c) minus "
       "the plan there, each relative to its gap, world axes; mean/std of |error| per axis over "
       "every trial with a traverse plan, successful or not (trials_without_plan aborted before "
       "planning); success needs the vehicle's footprint (body sphere, propeller disks, arms) "
       "clear of the panel and a hover after the gap; arrival_time_error_s = crossing - planned "
       "t_c over the trials that crossed"},
      {"ours", TableIFigures(result.trials)}};
  if (!result.paper_trials.empty()) {
    summary["table_i"]["paper"] = TableIFigures(result.paper_trials);
    nlohmann::json paper_per_trial = nlohmann::json::array();
    for (const GapTrialRecord& record : result.paper_trials) {
      paper_per_trial.push_back(GapTrialSummaryJson(record));
    }
    summary["paper_configuration"] = {
        {"mission_changes", {{"lead_in_s", PaperGapMissionParams(result.mission).lead_in_s}}},
        {"per_trial", paper_per_trial}};
  }
  summary["failures"] = CountFailures(result.trials);
  // Success by inclination: 15 deg roll bins x 15 deg pitch bins.
  std::map<std::pair<int, int>, std::pair<int, int>> bins;  // (roll, pitch) bin -> (ok, all)
  for (const GapTrialRecord& record : result.trials) {
    const std::pair<int, int> key{static_cast<int>(record.config.roll_deg / 15.0),
                                  static_cast<int>(record.config.pitch_deg / 15.0)};
    bins[key].second++;
    if (record.evaluation.success) bins[key].first++;
  }
  nlohmann::json by_inclination = nlohmann::json::array();
  for (const auto& [key, counts] : bins) {
    by_inclination.push_back({{"roll_deg", {15 * key.first, 15 * (key.first + 1)}},
                              {"pitch_deg", {15 * key.second, 15 * (key.second + 1)}},
                              {"trials", counts.second},
                              {"successes", counts.first},
                              {"success_rate", static_cast<double>(counts.first) / counts.second}});
  }
  summary["success_by_inclination"] = by_inclination;
  summary["per_trial"] = per_trial;
  if (!result.detector_sequences.empty()) {
    summary["detector"] = SummarizeGapDetectorSequences(result.detector_sequences,
                                                        result.options.detector_ranges.distance_m);
  }
  return summary;
}

}  // namespace aperture::experiments
