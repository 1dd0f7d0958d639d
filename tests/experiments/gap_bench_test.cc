// `aperture bench gap` harness with the ground-truth gap autopilot (no cameras): the flights
// succeed, results do not depend on the thread count, broken trials are recorded, and the
// outputs carry the documented keys.
#include "experiments/gap/gap_bench.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <stdexcept>

#include "config/yaml_write_archive.h"
#include "experiments/gap/ground_truth_gap_autopilot.h"
#include "planning/gap_mission/gap_mission_params_io.h"

namespace aperture::experiments {
namespace {

GapBenchOptions QuickOptions(int threads) {
  GapBenchOptions options;
  options.trials = 3;
  options.seed = 11;
  options.duration_s = 6.0;  // approach <= 2.5 s + traverse + 1.5 s braking + hover window
  options.threads = threads;
  options.render_cameras = false;
  options.paper_configuration = false;  // on in its own test below
  options.vehicle.mismatch = false;     // vehicle = model; on in its own test below
  return options;
}

// A fresh (emptied) folder of that name in the temporary directory.
std::filesystem::path FreshGapBenchDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  return dir;
}

TEST(GapBench, GroundTruthFlightsPassTheGapAndDoNotDependOnTheThreadCount) {
  const GapBenchResult serial = RunGapBench(QuickOptions(1), MakeGroundTruthGapAutopilotFactory());
  const GapBenchResult parallel =
      RunGapBench(QuickOptions(2), MakeGroundTruthGapAutopilotFactory());
  ASSERT_EQ(serial.trials.size(), 3u);
  EXPECT_EQ(serial.autopilot_name, "ground_truth_gap");
  for (std::size_t i = 0; i < serial.trials.size(); ++i) {
    const GapTrialRecord& a = serial.trials[i];
    const GapTrialRecord& b = parallel.trials[i];
    EXPECT_EQ(a.config.index, static_cast<int>(i));
    EXPECT_TRUE(a.evaluation.success) << a.evaluation.failure_reason;
    ASSERT_TRUE(a.evaluation.error.has_value());
    // Perfect state and gap: the PositionController tracks the traverse to within a few cm
    // (the opening leaves 12.5 cm / 8 cm of margin); 5 cm would already scrape the frame.
    EXPECT_LT(a.evaluation.error->position_m.norm(), 0.05) << "trial " << i;
    EXPECT_LT(std::abs(a.evaluation.error->time_s), 0.02) << "trial " << i;
    // Bit-identical across thread counts: every trial owns its seeded streams.
    ASSERT_TRUE(b.evaluation.error.has_value());
    EXPECT_EQ(a.evaluation.error->position_m, b.evaluation.error->position_m);
    EXPECT_EQ(a.evaluation.crossing->t_s, b.evaluation.crossing->t_s);
    // Fig. 6 traces: the estimate (= ground truth here) at every 100 Hz control step.
    EXPECT_EQ(a.estimate_trace.size(), a.truth_trace.size());
    EXPECT_GT(a.estimate_trace.size(), 500u);
  }
}

TEST(GapBench, APartStartingAtFirstTrialFliesTheSameTrialsAsTheWholeRun) {
  GapBenchOptions whole = QuickOptions(1);
  whole.trials = 2;
  GapBenchOptions part = whole;
  part.first_trial = 1;
  part.trials = 1;
  const GapBenchResult a = RunGapBench(whole, MakeGroundTruthGapAutopilotFactory());
  const GapBenchResult b = RunGapBench(part, MakeGroundTruthGapAutopilotFactory());
  ASSERT_EQ(b.trials.size(), 1u);
  EXPECT_EQ(b.trials[0].config.index, 1);
  EXPECT_EQ(b.trials[0].config.seed, a.trials[1].config.seed);
  ASSERT_TRUE(b.trials[0].evaluation.crossing.has_value());
  EXPECT_EQ(b.trials[0].evaluation.crossing->t_s, a.trials[1].evaluation.crossing->t_s);
}

TEST(GapBench, RecordsABrokenAutopilotAsAFailedTrial) {
  GapBenchOptions options = QuickOptions(1);
  options.trials = 1;
  const GapBenchResult result =
      RunGapBench(options, [](const GapTrialSetup&) -> std::unique_ptr<GapTrialAutopilot> {
        throw std::runtime_error("camera calibration missing");
      });
  ASSERT_EQ(result.trials.size(), 1u);
  EXPECT_EQ(result.trials[0].outcome, "error");
  EXPECT_FALSE(result.trials[0].evaluation.success);
  EXPECT_EQ(result.trials[0].evaluation.failure_reason, "error: camera calibration missing");
  const nlohmann::json summary = SummarizeGapBench(result);
  EXPECT_EQ(summary["successes"], 0);
  EXPECT_EQ(summary["error_at_gap"]["trials"], 0);
  EXPECT_EQ(summary["table_i"]["ours"]["trials_without_plan"], 1);  // counted, not hidden
}

TEST(GapBench, OptionsSurviveTheirJsonForm) {
  GapBenchOptions o = QuickOptions(2);
  o.first_trial = 4;
  o.ranges.min_roll_deg = 45.0;
  o.ranges.max_roll_deg = 60.0;
  o.ranges.start_offset_m = Eigen::Vector3d(0.1, 0.2, 0.3);
  o.ranges.motion_blur_subframes = 2;
  o.hover.min_height_m = 0.7;
  o.detector_sequences = 3;
  o.detector_ranges.distance_m = Eigen::Vector2d(2.0, 4.0);
  o.set_items = {"mission.lead_in_s=0"};
  const nlohmann::json json = GapBenchOptionsToJson(o);
  EXPECT_FALSE(json.contains("threads"));  // does not change a result
  const GapBenchOptions back = GapBenchOptionsFromJson(json);
  EXPECT_EQ(GapBenchOptionsToJson(back), json);
  EXPECT_EQ(back.ranges.min_roll_deg, 45.0);
  EXPECT_EQ(back.ranges.start_offset_m, o.ranges.start_offset_m);
  EXPECT_EQ(back.hover.min_height_m, 0.7);
  EXPECT_EQ(back.detector_ranges.distance_m, o.detector_ranges.distance_m);
  EXPECT_EQ(back.set_items, o.set_items);
  EXPECT_EQ(back.threads, 0);
  nlohmann::json broken = json;
  broken["ranges"].erase("min_roll_deg");
  try {
    GapBenchOptionsFromJson(broken);
    ADD_FAILURE() << "options without ranges.min_roll_deg were read";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("min_roll_deg"), std::string::npos) << e.what();
  }
}

TEST(GapBench, RunsTheDetectorSequencesAfterTheFlights) {
  GapBenchOptions options = QuickOptions(2);
  options.trials = 1;
  options.detector_sequences = 2;
  options.detector_ranges.duration_s = 0.06;  // 4 frames at 50 Hz
  options.detector_ranges.motion_blur_subframes = 1;
  int last_done = 0;
  const GapBenchResult result = RunGapBench(options, MakeGroundTruthGapAutopilotFactory(),
                                            [&](int done) { last_done = done; });
  ASSERT_EQ(result.trials.size(), 1u);
  ASSERT_EQ(result.detector_sequences.size(), 2u);
  EXPECT_EQ(last_done, 3);  // the flight and both sequences
  const GapBenchSetup setup = PrepareGapBench(options);
  for (int k = 0; k < 2; ++k) {
    const GapDetectorSequenceRecord& record = result.detector_sequences[k];
    EXPECT_EQ(record.config.index, k);
    EXPECT_TRUE(record.error.empty()) << record.error;
    // The same sequence as drawn and run alone: a pure function of (seed, index).
    const GapDetectorSequenceRecord alone = RunGapBenchDetectorSequence(options, setup, k);
    EXPECT_EQ(record.config.seed, alone.config.seed);
    ASSERT_EQ(record.frames.size(), alone.frames.size());
    ASSERT_FALSE(record.frames.empty());
    EXPECT_EQ(record.frames.back().distance_m, alone.frames.back().distance_m);
  }
}

TEST(GapBench, PaperConfigurationDropsOnlyTheLeadIn) {
  planning::GapMissionParams ours;
  ours.lead_in_s = 0.2;
  planning::GapMissionParams paper = PaperGapMissionParams(ours);
  EXPECT_EQ(paper.lead_in_s, 0.0);
  paper.lead_in_s = ours.lead_in_s;
  EXPECT_EQ(YAML::Dump(config::DumpParams(paper)), YAML::Dump(config::DumpParams(ours)))
      << "only lead_in_s differs";
}

// Each trial is flown twice, with the same draws: once with our mission, once with the paper's
// configuration; both reach summary.json's Table I and their own CSV.
TEST(GapBench, FliesEveryTrialAgainWithThePapersConfiguration) {
  GapBenchOptions options = QuickOptions(2);
  options.trials = 2;
  options.paper_configuration = true;
  std::mutex mutex;
  std::multiset<double> lead_ins;
  const GapTrialAutopilotFactory ground_truth = MakeGroundTruthGapAutopilotFactory();
  const GapBenchResult result = RunGapBench(options, [&](const GapTrialSetup& setup) {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      lead_ins.insert(setup.mission.lead_in_s);
    }
    return ground_truth(setup);
  });
  const double ours = PrepareGapBench(options).mission.lead_in_s;
  ASSERT_GT(ours, 0.0);
  EXPECT_EQ(lead_ins, (std::multiset<double>{0.0, 0.0, ours, ours}));
  ASSERT_EQ(result.paper_trials.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(result.paper_trials[i].config.seed, result.trials[i].config.seed);
    EXPECT_EQ(result.paper_trials[i].config.roll_deg, result.trials[i].config.roll_deg);
  }

  const std::filesystem::path dir = FreshGapBenchDir("aperture_gap_bench_paper_test");
  output::OutputFolder out(dir.string());
  WriteGapBenchOutputs(result, out);
  const nlohmann::json& summary = out.summary();
  for (const char* configuration : {"ours", "paper"}) {
    const nlohmann::json& table = summary["table_i"][configuration];
    EXPECT_EQ(table["trials"], 2) << configuration;
    EXPECT_EQ(table["trials_with_plan"], 2) << configuration;
    EXPECT_EQ(table["successes"], 2) << configuration;
  }
  // Table I's mean |error| is the mean over the per-trial errors at the planned t_c.
  const nlohmann::json& per_trial = summary["paper_configuration"]["per_trial"];
  ASSERT_EQ(per_trial.size(), 2u);
  const double z0 = per_trial[0]["error_at_planned_tc"]["position_m"][2].get<double>();
  const double z1 = per_trial[1]["error_at_planned_tc"]["position_m"][2].get<double>();
  EXPECT_NEAR(summary["table_i"]["paper"]["position_mean"][2].get<double>(),
              0.5 * (std::abs(z0) + std::abs(z1)), 1e-12);
  EXPECT_TRUE(std::filesystem::exists(dir / "paper_trials.csv"));
  std::filesystem::remove_all(dir);
}

// vehicle.mismatch: the simulated vehicle is drawn per trial while the autopilot keeps the
// nominal model, so the same trial flies a different path.
TEST(GapBench, FliesAVehicleThatIsNotTheAutopilotsModel) {
  GapBenchOptions options = QuickOptions(2);
  options.trials = 2;
  const GapBenchResult model = RunGapBench(options, MakeGroundTruthGapAutopilotFactory());
  options.vehicle.mismatch = true;
  std::mutex mutex;
  std::vector<control::VehicleParameters> given;
  const GapTrialAutopilotFactory ground_truth = MakeGroundTruthGapAutopilotFactory();
  const GapBenchResult mismatched = RunGapBench(options, [&](const GapTrialSetup& setup) {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      given.push_back(setup.vehicle);
    }
    return ground_truth(setup);
  });
  const control::VehicleParameters nominal;
  ASSERT_EQ(given.size(), 2u);
  for (const control::VehicleParameters& vehicle : given) {
    EXPECT_EQ(vehicle.rotor.thrust_coeffs_N, nominal.rotor.thrust_coeffs_N);
    EXPECT_EQ(vehicle.rotor_drag_D_per_s, nominal.rotor_drag_D_per_s);
  }
  for (int i = 0; i < 2; ++i) {
    const std::vector<control::QuadState>& a = model.trials[i].truth_trace;
    const std::vector<control::QuadState>& b = mismatched.trials[i].truth_trace;
    ASSERT_GT(std::min(a.size(), b.size()), 100u) << "trial " << i;
    EXPECT_NE(a[100].p_WB, b[100].p_WB) << "trial " << i;  // 1 s in: another vehicle
  }
}

TEST(GapBench, WritesSummaryTrialsCsvAndReport) {
  GapBenchOptions options = QuickOptions(0);
  options.trials = 2;
  const GapBenchResult result = RunGapBench(options, MakeGroundTruthGapAutopilotFactory());
  const std::filesystem::path dir = FreshGapBenchDir("aperture_gap_bench_test");
  output::OutputFolder out(dir.string());
  WriteGapBenchOutputs(result, out);
  const nlohmann::json& summary = out.summary();
  EXPECT_EQ(summary["trials"], 2);
  EXPECT_EQ(summary["successes"], 2);
  EXPECT_DOUBLE_EQ(summary["success_rate"].get<double>(), 1.0);
  for (const char* key : {"position_mean", "position_std", "velocity_mean", "velocity_std"}) {
    ASSERT_EQ(summary["error_at_gap"][key].size(), 3u) << key;
  }
  for (const char* key : {"orientation_mean_deg", "orientation_std_deg"}) {
    ASSERT_EQ(summary["error_at_gap"][key].size(), 2u) << key;
  }
  // Mean |error| per axis is the mean of the per-trial |errors|.
  const nlohmann::json& per_trial = summary["per_trial"];
  ASSERT_EQ(per_trial.size(), 2u);
  const double x0 = per_trial[0]["error_at_gap"]["position_m"][0].get<double>();
  const double x1 = per_trial[1]["error_at_gap"]["position_m"][0].get<double>();
  EXPECT_NEAR(summary["error_at_gap"]["position_mean"][0].get<double>(),
              0.5 * (std::abs(x0) + std::abs(x1)), 1e-12);
  EXPECT_EQ(per_trial[0]["roll_deg"], result.trials[0].config.roll_deg);
  EXPECT_EQ(per_trial[0]["outcome"], "duration_reached");
  std::ifstream csv(dir / "trials.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 3);  // header + 2 trials
  EXPECT_GT(std::filesystem::file_size(dir / "report.html"), 1000u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace aperture::experiments
