// aperture sim: fly a scenario closed-loop in the lockstep SITL simulator.
//
//   aperture sim NAME [--config FILE] [--set key=value ...] [--seed N] [--duration S] --out DIR
//   aperture sim tracking ... | aperture sim recovery ...   (sim_tracking/recovery_command.cc)
//
// NAME is a built-in scenario (sim/scenario); --config/--set override its keys (a summary.json of
// an earlier run as --config: its full effective configuration, the same flight). The vehicle
// starts at the scenario's start pose and flies a mission of the registry
// (experiments/missions/builtin_missions.h): --mission (or mission.name), else the scenario's
// default (`gap`: the vision gap mission, `led`: the LED-stabilized hover, `tags`: the tag
// mapping flight, ...; `--set mission=NAME` is mission.name), with its parameters from the
// `mission` section (--set mission.<key>=<value>); its
// ground-truth evaluation goes into summary.json "mission" (name, passed, its figures) and its
// report sections into report.html. Writes OUT/summary.json (outcome, crash reason and
// contact point, real_time_factor, timing, hover errors, frame statistics), OUT/trajectory.csv
// and OUT/trajectory.tum (ground truth), OUT/commands.csv, OUT/imu.csv, OUT/sim.mp4 (or .avi: the
// onboard camera with overlays beside a third-person view from behind the vehicle) and
// OUT/report.html (position and command plots, key frames), and the mission's own files
// (MissionFlight::WriteFiles, e.g. the tag map's).
// --fault NAME=LEVEL [--fault-seed N] injects one fault of `aperture bench faults` after the
// mission was built (experiments/faults/fault_injection.h): a failing bench flight flown again with
// video (its flights.csv gives the command in its replay column).
// SIGINT/SIGTERM end the flight at the next simulation step (outcome "stopped"): every output is
// then written for the flight so far (the video finalised with its frames) and summary.json says
// "status": "interrupted" (exit 130/143).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "apps/chase_view.h"
#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/path_views.h"
#include "apps/sitl_outputs.h"
#include "config/config_tree.h"
#include "config/usage_error.h"
#include "experiments/faults/fault_injection.h"
#include "experiments/led/led_hover_flight.h"
#include "experiments/missions/builtin_missions.h"
#include "output/background_video_writer.h"
#include "output/html_report.h"
#include "output/interruption.h"
#include "output/progress_bar.h"
#include "output/svg_plot.h"
#include "perception/cpu_time.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_sitl.h"
#include "sim/sim_params_io.h"
#include "sim/sitl/sitl_runner.h"

namespace aperture::apps {
namespace {

constexpr double kDefaultDurationS = 10.0;

struct SimOptions {
  CommonOptions common;
  std::string scenario;
  std::string mission;  // empty: the scenario's default
  std::optional<std::uint64_t> seed;
  // Simulated time [s]; unset: 10 s or the mission's own flight time if longer
  // (MissionFlight::MinimumDurationS).
  std::optional<double> duration_s;
  int video_every = 2;  // camera frames per video frame (30 Hz camera: 15 frames/s video)
  // --fault NAME=LEVEL: one fault of `aperture bench faults` injected after the mission was
  // built (it is not told of it); --fault-seed: its draw (direction, onset), default the seed.
  std::string fault;
  std::optional<std::uint64_t> fault_seed;
  ChaseViewParams chase;
};

cv::Mat ToBgr(const cv::Mat& image) {
  cv::Mat bgr;
  if (image.channels() == 1) {
    cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  } else {
    bgr = image.clone();
  }
  return bgr;
}

void PutLines(cv::Mat* image, const std::vector<std::string>& lines) {
  const double scale = std::max(0.35, image->rows / 800.0);
  int y = static_cast<int>(18 * scale / 0.5);
  for (const std::string& line : lines) {
    cv::putText(*image, line, {6, y}, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 3);
    cv::putText(*image, line, {6, y}, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 255, 255), 1);
    y += static_cast<int>(22 * scale / 0.5);
  }
}

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0) {
  char buffer[128];
  std::snprintf(buffer, sizeof(buffer), format, a, b, c);
  return buffer;
}

nlohmann::json Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// The verdict a reader looks for: the mission's own ground-truth evaluation (passed the gap, held
// the hover, ...), and the headline figures.
output::ReportOutcome SimOutcome(const sim::SitlResult& result, const nlohmann::json& summary,
                                 const experiments::MissionEvaluation& evaluation) {
  output::ReportOutcome outcome;
  outcome.verdict = evaluation.passed ? "passed" : "failed";
  outcome.headline = evaluation.outcome + Format(" (%.2f s simulated)", result.sim_time_s);
  const nlohmann::json& figures = evaluation.figures;
  if (figures.contains("error_at_gap")) {
    const nlohmann::json& p = figures["error_at_gap"]["position_m"];
    outcome.figures.push_back({"position error at the gap (x, y, z)",
                               Format("%.1f, %.1f, %.1f cm", 100 * p[0].get<double>(),
                                      100 * p[1].get<double>(), 100 * p[2].get<double>()),
                               "seed 000 Table I: mean |error| 4, 4, 3 cm"});
  }
  outcome.figures.push_back(
      {"hover error from the start (RMS / max)",
       Format("%.1f / %.1f cm", 100 * summary["hover_error_m"]["rms"].get<double>(),
              100 * summary["hover_error_m"]["max"].get<double>()),
       ""});
  if (result.collision) {
    outcome.figures.push_back({"collision", result.collision->object_name, "none"});
  }
  outcome.figures.push_back({"real-time factor", Format("%.2f", result.real_time_factor), ""});
  return outcome;
}

void WriteReport(const sim::SitlResult& result, const std::vector<cv::Mat>& key_frames,
                 const std::string& title, const sim::Scenario& scenario, output::OutputFolder& out,
                 const experiments::MissionFlight& flight,
                 const experiments::MissionEvaluation& evaluation) {
  output::HtmlReport report(title);
  report.AddOutcome(SimOutcome(result, out.summary(), evaluation));
  report.AddRunDescription(out.summary(), out.ElapsedSeconds());
  std::vector<std::string> riding_on_vehicle = scenario.AttachedObjectNames();
  riding_on_vehicle.push_back(ChaseView::kMarkerName);
  AddPathViews(result.trajectory, scenario.scene(), riding_on_vehicle, &report);
  flight.AddReportSections(evaluation, result, &report);
  std::vector<double> t, x, y, z;
  for (const control::QuadState& s : result.trajectory) {
    t.push_back(s.t_s);
    x.push_back(s.p_WB.x());
    y.push_back(s.p_WB.y());
    z.push_back(s.p_WB.z());
  }
  report.AddSection("Trajectory");
  report.AddSvg(output::SvgPlot({"Position (ground truth)", "t [s]", "p_WB [m]"})
                    .AddLine("x", t, x)
                    .AddLine("y", t, y)
                    .AddLine("z", t, z)
                    .Render());
  AddSitlCommandPlots(result, &report);
  if (!key_frames.empty()) {
    report.AddSection("Key frames (onboard | third person)");
    for (const cv::Mat& frame : key_frames) {
      report.AddImage(frame, "", output::HtmlReport::ImageEncoding::kJpeg);
    }
  }
  report.AddCollapsedTable(out.summary(), "Every figure of summary.json");
  report.Write(out.Path("report.html"));
}

void RunSim(const SimOptions& options, output::OutputFolder& out) {
  // Ctrl-C / SIGTERM end the flight at the next step; its outputs are then written as usual.
  const output::InterruptionHandlers interruption;
  std::vector<std::string> set_items = options.common.set_items;
  if (options.seed) set_items.push_back("seed=" + std::to_string(*options.seed));
  // `--set mission=NAME` (issue 15's spelling) names the mission: `--set mission.name=NAME`.
  const std::string mission_item = "mission=";
  for (std::string& item : set_items) {
    if (item.rfind(mission_item, 0) == 0 && item.size() > mission_item.size() &&
        item[mission_item.size()] != '{') {
      item.insert(mission_item.size() - 1, ".name");
    }
  }
  config::ConfigTree tree =
      sim::ScenarioConfig(options.scenario, options.common.config_files, set_items);
  config::ParamReader root = tree.Reader();
  sim::ScenarioParams scenario_params;
  LoadParams(root, &scenario_params);
  // The `mission` section: which mission (`name`; --mission wins) and its parameters.
  config::ParamReader mission_params = root.Section("mission");
  root.RejectUnknownKeys();
  std::string mission_name = options.mission;
  if (mission_name.empty()) mission_params.Read("name", &mission_name);
  sim::Scenario scenario = sim::BuildScenario(scenario_params);

  sim::SitlRunnerParams params;
  params.duration_s = options.duration_s.value_or(kDefaultDurationS);
  params.trajectory_decimation = 5;  // 200 Hz ground truth in the outputs
  sim::ConfigureSitlFromScenario(scenario, &params);
  for (sim::SitlCamera& camera : params.cameras) camera.render.ground_truth = false;
  params.SetSeed(scenario_params.seed);
  CheckAssembled(tree, [&] { params.Validate(); });  // e.g. a --set camera rate above the loop's
  // The video shows the first body-mounted camera (else the first camera) beside a third-person
  // view of the same height.
  int primary = 0;
  for (int i = static_cast<int>(params.cameras.size()) - 1; i >= 0; --i) {
    if (!params.cameras[i].T_WC_fixed) primary = i;
  }
  const int view_height = params.cameras.empty() ? 480 : params.cameras[primary].model->height();
  ChaseView chase(options.chase, view_height, &scenario.scene());
  params.collision.ignored_objects.push_back(ChaseView::kMarkerName);

  experiments::MissionRegistry missions;
  experiments::RegisterBuiltinMissions(missions);
  if (mission_name.empty()) mission_name = missions.DefaultFor(scenario_params.scenario);
  const std::unique_ptr<experiments::MissionFlight> flight =
      missions.Create(mission_name, {scenario, params, mission_params});
  if (!options.duration_s) {
    params.duration_s = std::max(params.duration_s, flight->MinimumDurationS());
  }
  nlohmann::json fault_input;  // summary.json inputs.fault
  if (!options.fault.empty()) {
    const experiments::FaultSetting fault = experiments::ParseFaultSetting(options.fault);
    const std::uint64_t fault_seed = options.fault_seed.value_or(scenario_params.seed);
    experiments::InjectFault(fault.fault->kind, fault.level, experiments::DrawFault(fault_seed),
                             &params);
    fault_input = {{"name", fault.fault->name}, {"level", fault.level}, {"fault_seed", fault_seed}};
  }
  perception::Autopilot& autopilot = flight->autopilot();
  sim::SitlRunner runner(params, &scenario.scene());

  std::unique_ptr<output::BackgroundVideoWriter> video;
  std::vector<cv::Mat> key_frames;
  const int frames_expected =
      params.cameras.empty()
          ? 0
          : static_cast<int>(params.duration_s * params.cameras[primary].rate_hz);
  // The video takes every video_every-th camera frame (the others cost nothing here); at most
  // ~kMaxKeyFrames evenly spaced video frames go into the report (JPEG), whatever the duration.
  const int video_frames_expected = frames_expected / options.video_every;
  constexpr int kMaxKeyFrames = 8;
  const int key_frame_every =
      std::max(1, (video_frames_expected + kMaxKeyFrames - 1) / kMaxKeyFrames);
  output::ProgressBar progress("frames", static_cast<std::size_t>(frames_expected));
  int frames_seen = 0, video_frames = 0;
  sim::SitlHooks hooks = experiments::MakeMissionHooks(flight.get(), &scenario);
  hooks.stop_requested = [] { return output::InterruptionRequested(); };
  hooks.on_frame = [&](int camera_index, const sim::CapturedFrame& captured,
                       const control::QuadState& state) {
    if (camera_index != primary) return;
    progress.Update(static_cast<std::size_t>(++frames_seen));
    if ((frames_seen - 1) % options.video_every != 0) return;
    cv::Mat onboard = ToBgr(captured.frame.image);
    PutLines(&onboard,
             {params.cameras[primary].name + Format("  t = %.2f s", state.t_s),
              Format("p = [%.2f %.2f %.2f] m", state.p_WB.x(), state.p_WB.y(), state.p_WB.z()),
              Format("|v| = %.2f m/s", state.v_W.norm()), autopilot.status()});
    flight->DrawOverlay(onboard);
    const bool key_frame = video_frames % key_frame_every == 0;
    cv::Mat composite;
    cv::hconcat(onboard, chase.Update(video_frames, state, key_frame), composite);
    cv::Mat third_person = composite.colRange(onboard.cols, composite.cols);
    PutLines(&third_person, {"third person"});
    if (!video) {
      video = std::make_unique<output::BackgroundVideoWriter>(
          out.Path("sim"), params.cameras[primary].rate_hz / options.video_every);
    }
    video->Write(composite);
    if (key_frame) key_frames.push_back(composite);
    ++video_frames;
  };
  const sim::SitlResult result = runner.Run(autopilot, hooks);
  progress.Finish();
  const double outputs_cpu_start_s = perception::ProcessCpuSeconds();

  nlohmann::json& summary = out.summary();
  summary["command"] = "sim";
  summary["inputs"] = {{"scenario", options.scenario},
                       {"mission", mission_name},
                       {"seed", scenario_params.seed},
                       {"duration_s", params.duration_s},
                       {"autopilot", result.autopilot_name}};
  if (!fault_input.is_null()) summary["inputs"]["fault"] = fault_input;
  // The full effective configuration: `--config OUT/summary.json` flies this run again.
  sim::PutEffectiveSitlBlocks(scenario_params, &tree);
  PutEffectiveLeds(scenario_params, &tree);
  tree.PutParams("imu", params.imu);  // with the noise seeds SetSeed derived from `seed`
  tree.PutParams("range", params.range);
  YAML::Node mission_config = flight->EffectiveParams();
  mission_config["name"] = mission_name;
  tree.Put("mission", mission_config, "effective configuration");
  summary["config"] = nlohmann::json::parse(tree.ToJson());
  AddSitlRunSummary(result, &summary);
  summary["timing"]["chase_render_s"] = chase.render_s();  // part of hooks_s
  summary["video"] = {
      {"frames", video_frames},
      {"rate_hz",
       params.cameras.empty() ? 0.0 : params.cameras[primary].rate_hz / options.video_every},
      {"chase_renders", chase.renders()}};
  if (result.collision) {
    summary["collision"] = {{"object", result.collision->object_name},
                            {"part", result.collision->part},
                            {"contact_p_W_m", Vec(result.collision->contact_p_W)}};
  }
  const experiments::HoverMetrics hover = experiments::ComputeHoverMetrics(
      result.trajectory, params.initial_state.p_WB, {}, /*recovery_radius_m=*/0.1,
      /*recovery_hold_s=*/1.0);
  summary["hover_error_m"] = {{"max", hover.max_error_m}, {"rms", hover.rms_error_m}};
  nlohmann::json cameras = nlohmann::json::array();
  for (const sim::SitlCameraStats& c : result.cameras) {
    cameras.push_back({{"name", c.name},
                       {"frames_due", c.frames_due},
                       {"frames_dropped", c.frames_dropped},
                       {"frames_delivered", c.frames_delivered}});
  }
  summary["cameras"] = cameras;
  const experiments::MissionEvaluation evaluation = flight->Evaluate(result);
  nlohmann::json& mission_summary = summary["mission"];
  mission_summary = evaluation.figures;
  mission_summary["name"] = mission_name;
  mission_summary["passed"] = evaluation.passed;
  WriteSitlTimeSeries(result, out);
  nlohmann::json outputs = {{"trajectory", "trajectory.csv"},
                            {"tum", "trajectory.tum"},
                            {"commands", "commands.csv"},
                            {"imu", "imu.csv"},
                            {"report", "report.html"}};
  if (video) {
    if (const std::optional<std::string> path = video->Close()) {
      outputs["video"] = std::filesystem::path(*path).filename().string();
    }
  }
  for (const auto& [key, file] : flight->WriteFiles(out.directory())) outputs[key] = file;
  summary["outputs"] = outputs;
  WriteReport(result, key_frames, "aperture sim: " + options.scenario, scenario, out, *flight,
              evaluation);
  // After the flight: the evaluation, the video's last frames, CSV files and report.html.
  summary["timing"]["cpu"]["outputs_after_flight_s"] =
      perception::ProcessCpuSeconds() - outputs_cpu_start_s;
  std::cout << "aperture sim " << options.scenario << ": " << sim::ToString(result.outcome) << " ("
            << result.reason << ") after " << result.sim_time_s << " s, real-time factor "
            << result.real_time_factor << "\n";
  std::cout << evaluation.outcome << "\n";
}

}  // namespace

void AddSimCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<SimOptions>();
  CLI::App* command =
      app.add_subcommand("sim", "Fly a scenario closed-loop in the rendered simulator (SITL)");
  command->add_option("scenario", options->scenario,
                      "Built-in scenario: " + BuiltinScenarioList() + "; or a flow below");
  command->add_option(
      "--mission", options->mission,
      "Mission to fly (gap, gapflyt, led_hover, forest, map, follow, hover); default: the "
      "scenario's own");
  AddSeedOption(command, &options->seed, "Seed of the scenario and every sensor stream");
  command
      ->add_option("--duration", options->duration_s,
                   "Simulated time [s] (default 10, or the mission's flight time if longer)")
      ->check(FiniteNumberIn(0.0, kMaxDurationS, /*min_inclusive=*/false));
  command
      ->add_option("--video-every", options->video_every,
                   "Put every N-th camera frame into the video (default 2; the video's frame "
                   "rate is the camera's / N)")
      ->check(IntegerIn(1));
  command
      ->add_option("--chase-every", options->chase.render_every,
                   "Render the video's third-person view every N-th video frame, repeat it "
                   "in between (default 2)")
      ->check(IntegerIn(1));
  command
      ->add_option("--chase-height", options->chase.render_height,
                   "Rows the third-person view is rendered at, scaled to the video "
                   "(default 240 px)")
      ->check(IntegerIn(16, 2160));
  command
      ->add_option("--fault", options->fault,
                   "Inject one fault of `aperture bench faults` that the mission is not told of, "
                   "NAME=LEVEL (e.g. motor_loss=0.15; flights.csv's replay column)")
      ->check([](const std::string& text) {
        try {
          experiments::ParseFaultSetting(text);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      });
  command
      ->add_option("--fault-seed", options->fault_seed,
                   "Seed of the fault's direction and onset (default: the run's seed)")
      ->check(SeedValidator());
  AddCommonOptions(command, &options->common);
  // Flows with their own options (apps/sim_<flow>_command.cc); a scenario run needs NAME and --out.
  command->get_option("--out")->required(false)->description(
      "Output folder (created if missing); REQUIRED with a scenario NAME");
  AddSimTrackingCommand(*command, exit_code);
  AddSimRecoveryCommand(*command, exit_code);
  command->callback([command, options, exit_code] {
    if (!command->get_subcommands().empty()) return;
    if (options->scenario.empty()) {
      throw config::UsageError("a scenario NAME is required: one of " + BuiltinScenarioList() +
                               "; or a flow: tracking, recovery");
    }
    if (options->common.out_dir.empty()) throw CLI::RequiredError("--out");
    RequireBuiltinScenario(options->scenario);
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] { RunSim(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
