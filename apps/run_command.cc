// aperture run: perception front ends on a camera, a video or an image sequence.
//
//   aperture run --source DIR|VIDEO|BAG|camera:N --frontends image_quality --out OUT [--video]
//   aperture run --source FILE.bag --image-topic T [--imu-topic T] [--camera-info-topic T] ...
//
// Writes OUT/summary.json (inputs, effective config, frame counts, skipped frames, per-node
// timing, metric statistics), OUT/frames.csv (one row per frame: t_s, index, every node metric),
// OUT/report.html (metric plots, timing, key frames with overlays) and with --video the overlay
// video OUT/overlay.mp4 (or .avi); a source with an IMU (a bag with --imu-topic) adds OUT/imu.csv
// and hands each frame its IMU samples (ts2p derotates with them).
// Front ends may add their own files (FrontEndResources::output_directory), e.g. ts2p:
// OUT/openings/<index>.png and OUT/ts2p.csv; gap_tracker: OUT/gap_tracker.csv.
// SIGINT/SIGTERM stop it after the current frame, and a source that fails after frames (a camera
// that disconnects) ends the frame loop: every output is then closed with the frames so far and
// summary.json says "interrupted" (exit 130/143) or "failed" with the source's error (exit 1).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "apps/imu_csv.h"
#include "apps/pose_streams.h"
#include "apps/run_report.h"
#include "apps/stoppable_frame_source.h"
#include "output/csv_writer.h"
#include "output/interruption.h"
#include "output/progress_bar.h"
#include "output/video_writer.h"
#include "perception/camera/calibration_io.h"
#include "perception/graph/builtin_front_ends.h"
#include "perception/graph/front_end_registry.h"
#include "perception/graph/parallel_executor.h"
#include "perception/graph/serial_executor.h"
#include "perception/graph/source_run.h"
#include "perception/io/open_frame_source.h"
#include "perception/io/rosbag_source.h"
#include "servo/visp_tag_detector.h"

namespace aperture::apps {
namespace {

struct RunOptions {
  CommonOptions common;
  std::string source;
  double fps = 0.0;
  bool color = false;
  bool skip_bad_frames = false;
  std::string front_ends = "image_quality";
  std::string calibration_path;
  std::string kalibr_camera;  // --camera: the camera of a Kalibr camchain (empty: its only one)
  std::string image_topic, imu_topic, camera_info_topic;
  bool parallel = false;
  bool video = false;
  int max_frames = 0;
};

void RunFrontEnds(const RunOptions& options, output::OutputFolder& out) {
  // Ctrl-C / SIGTERM end the frame loop; the outputs are then closed as at the end of the source.
  const output::InterruptionHandlers interruption;
  const config::ConfigTree tree = LoadConfig(options.common, "");
  const std::vector<std::string> front_end_names =
      perception::SplitFrontEndList(options.front_ends);
  perception::FrontEndResources resources;
  resources.source = options.source;
  if (!options.calibration_path.empty() && !options.camera_info_topic.empty()) {
    throw std::invalid_argument(
        "give the calibration either as --calib FILE or as "
        "--camera-info-topic TOPIC of the bag, not both");
  }
  if (!options.calibration_path.empty()) {
    resources.calibration =
        perception::LoadCameraCalibration(options.calibration_path, options.kalibr_camera);
  } else if (!options.camera_info_topic.empty()) {
    resources.calibration =
        perception::LoadCameraInfoFromBag(options.source, options.camera_info_topic);
  }
  resources.output_directory = out.directory();
  resources.tag_detectors.Register(servo::kVispTagDetectorName, &servo::CreateVispTagDetector);
  perception::FrontEndRegistry registry;
  perception::RegisterBuiltinFrontEnds(registry);
  // Each front end reads the config section named after it; any other section is a typo.
  config::ParamReader root = tree.Reader();
  perception::FrameGraph graph = registry.BuildGraph(front_end_names, root, resources);
  root.RejectUnknownKeys();

  perception::FrameSourceOptions source_options;
  source_options.fps = options.fps;
  source_options.color_mode =
      options.color ? perception::ColorMode::kColor : perception::ColorMode::kGray;
  source_options.skip_bad_frames = options.skip_bad_frames;
  source_options.image_topic = options.image_topic;
  source_options.imu_topic = options.imu_topic;
  const std::unique_ptr<StoppableFrameSource> source = std::make_unique<StoppableFrameSource>(
      perception::OpenFrameSource(options.source, source_options));

  nlohmann::json& summary = out.summary();
  summary["command"] = "run";
  summary["inputs"] = {
      {"source", options.source},
      {"source_description", source->Describe()},
      {"front_ends", front_end_names},
      {"calibration", resources.calibration ? resources.calibration->source_path : std::string()},
      {"executor", options.parallel ? "parallel" : "serial"}};
  summary["config"] = nlohmann::json::parse(tree.ToJson());

  std::unique_ptr<perception::FrameGraphExecutor> executor;
  if (options.parallel) {
    executor = std::make_unique<perception::ParallelExecutor>(graph);
  } else {
    executor = std::make_unique<perception::SerialExecutor>(graph);
  }
  std::size_t expected = source->SizeHint().value_or(0);
  if (options.max_frames > 0 && (expected == 0 || expected > size_t(options.max_frames))) {
    expected = options.max_frames;
  }
  output::ProgressBar progress("frames", expected);
  std::unique_ptr<output::CsvWriter> csv;
  std::vector<std::string> metric_names;
  std::unique_ptr<output::VideoWriter> video;
  std::unique_ptr<output::CsvWriter> imu_csv;
  std::size_t imu_samples = 0;
  PoseStreams pose_streams(out);
  RunRecord record;
  perception::RunSource(
      *source, graph, *executor, resources, options.max_frames,
      [&](const perception::Frame& frame, const perception::FrameSlots& slots) {
        for (const perception::ImuSample& imu : frame.imu) {
          if (!imu_csv) imu_csv = MakeImuCsv(out.Path("imu.csv"));
          WriteImuRow(*imu_csv, imu);
          ++imu_samples;
        }
        const std::map<std::string, double> metrics = graph.CollectMetrics(slots);
        if (!csv) {
          std::vector<std::string> columns{"t_s", "index"};
          for (const auto& [name, value] : metrics) metric_names.push_back(name);
          columns.insert(columns.end(), metric_names.begin(), metric_names.end());
          csv = std::make_unique<output::CsvWriter>(out.Path("frames.csv"), columns);
        }
        std::vector<double> row{frame.t_s, double(frame.index)};
        for (const std::string& name : metric_names) {
          const auto it = metrics.find(name);
          if (it == metrics.end()) {
            throw std::logic_error("front end metric '" + name + "' missing at frame " +
                                   std::to_string(frame.index) +
                                   " (metrics must be emitted every frame)");
          }
          row.push_back(it->second);
        }
        csv->WriteRow(row);
        pose_streams.Write(frame.t_s, graph.CollectPoses(slots));
        const cv::Mat overlay = graph.RenderOverlay(slots);
        if (options.video) {
          if (!video) {
            // Sequences without a rate play back at 30 Hz, a typical camera rate.
            video = std::make_unique<output::VideoWriter>(out.Path("overlay"),
                                                          options.fps > 0 ? options.fps : 30.0);
          }
          video->Write(overlay);
        }
        record.Add(frame, row, overlay, expected);
        progress.Update(record.frame_count());
      });
  progress.Finish();
  csv->Close();
  const std::map<std::string, std::string> front_end_files = graph.Finish();

  summary["frames"] = record.frame_count();
  summary["skipped_frames"] = source->source().SkippedFrames().size();
  summary["imu_samples"] = imu_samples;
  nlohmann::json skipped = nlohmann::json::array();
  for (const auto& skip : source->source().SkippedFrames()) {
    skipped.push_back({{"item", skip.item}, {"reason", skip.reason}});
  }
  summary["skipped"] = skipped;
  summary["timing"] = TimingJson(executor->Timing(), executor->FrameTiming());
  summary["metrics"] = record.MetricStatistics(metric_names);
  nlohmann::json outputs = {{"csv", "frames.csv"}, {"report", "report.html"}};
  for (const auto& [key, file] : front_end_files) outputs[key] = file;
  summary["poses"] = pose_streams.Close();
  if (imu_csv) {
    imu_csv->Close();
    outputs["imu"] = "imu.csv";
  }
  if (video) {
    if (const std::optional<std::string> path = video->Close()) {
      outputs["video"] = std::filesystem::path(*path).filename().string();
    }
  }
  summary["outputs"] = outputs;
  WriteRunReport(out, record, metric_names);
  // A source that failed after frames: every output is complete up to there; the run failed.
  if (source->failure()) throw std::runtime_error(*source->failure());
}

}  // namespace

void AddRunCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* command =
      app.add_subcommand("run", "Run perception front ends on a camera, video or image folder");
  command
      ->add_option("--source", options->source,
                   "Image folder, video file, ROS1 bag (FILE.bag, with --image-topic), or "
                   "camera:N (device index)")
      ->required();
  command->add_option("--image-topic", options->image_topic,
                      "ROS bag: the sensor_msgs/Image or CompressedImage topic to read");
  command->add_option("--imu-topic", options->imu_topic,
                      "ROS bag: a sensor_msgs/Imu topic; its samples go to OUT/imu.csv");
  command->add_option("--camera-info-topic", options->camera_info_topic,
                      "ROS bag: take the calibration from this sensor_msgs/CameraInfo topic "
                      "instead of --calib");
  perception::FrontEndRegistry registry;
  perception::RegisterBuiltinFrontEnds(registry);
  std::string known;
  for (const std::string& name : registry.Names()) known += (known.empty() ? "" : ", ") + name;
  command->add_option("--frontends", options->front_ends,
                      "Comma-separated front ends to run (known: " + known + ")");
  command->add_option("--fps", options->fps, "Frame rate [Hz] for sources without timestamps")
      ->check(FiniteNumberIn(kMinFps, kMaxFps));
  command->add_flag("--color", options->color, "Read colour (BGR) frames instead of gray");
  command->add_flag("--skip-bad-frames", options->skip_bad_frames,
                    "Skip corrupt, truncated or wrong-size frames with a warning (counted in "
                    "summary.json) instead of failing");
  command
      ->add_option("--calib", options->calibration_path,
                   "Camera calibration (OpenCV, ROS camera_info or Kalibr YAML)")
      ->check(CLI::ExistingFile);
  command->add_option("--camera", options->kalibr_camera,
                      "Camera of a Kalibr camchain given to --calib (cam0, cam1, ...; default: "
                      "its only camera, an error when it holds several)");
  command->add_flag("--parallel", options->parallel,
                    "Run independent front ends concurrently (oneTBB)");
  command->add_flag("--video", options->video, "Write the overlay video");
  command->add_option("--max-frames", options->max_frames, "Stop after N frames (0 = all)")
      ->check(IntegerIn(0));
  AddCommonOptions(command, &options->common);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] { RunFrontEnds(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
