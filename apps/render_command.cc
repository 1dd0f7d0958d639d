// aperture render: a dataset with ground truth from a simulator scenario.
//
//   aperture render gap --trajectory line --frames 60 [--seed 3] --out OUT
//                  [--config scenario.yaml] [--set gap.roll_deg=30]
//
// Writes, for the scenario's render camera moved along a kinematic trajectory:
//   OUT/images/000000.png ...  camera frames (8-bit gray or BGR) + OUT/images/times.txt (seconds,
//                              one line per image: ImageFolderSource reads it from there)
//   OUT/depth/000000.png ...   16-bit depth z_C [mm], 0 = no surface
//   OUT/masks/000000.png ...   16-bit object ids (0 = sky; names in summary.json "objects")
//   OUT/groundtruth.txt        T_WC per frame, TUM format (t tx ty tz qx qy qz qw)
//   OUT/objects.csv            T_WO per frame of every object: t,name,tx,ty,tz,qx,qy,qz,qw
//   OUT/calib.yaml             camera calibration (OpenCV format, with T_BC)
//   OUT/scenario.yaml          effective scenario configuration (reproduces the run)
//   OUT/summary.json, OUT/report.html
// so that `aperture run --source OUT --calib OUT/calib.yaml` replays the dataset.
// SIGINT/SIGTERM stop it after the current frame: every file then covers the frames written
// (times.txt one line per image), summary.json says "status": "interrupted", "frames": the count
// (exit 130/143).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <sstream>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "config/usage_error.h"
#include "output/csv_writer.h"
#include "output/html_report.h"
#include "output/interruption.h"
#include "output/progress_bar.h"
#include "output/svg_plot.h"
#include "output/tum_trajectory_writer.h"
#include "perception/camera/calibration_io.h"
#include "sim/scenario/ground_truth_images.h"
#include "sim/scenario/kinematic_trajectory.h"
#include "sim/scenario/scenario.h"

namespace aperture::apps {
namespace {

struct RenderCommandOptions {
  CommonOptions common;
  std::string scenario;
  std::string trajectory;             // empty: the scenario's default
  int frames = 0;                     // 0: the scenario's default
  std::optional<std::uint64_t> seed;  // unset: the scenario's seed
};

void WritePng(const std::string& path, const cv::Mat& image) {
  if (!cv::imwrite(path, image)) throw std::runtime_error("cannot write image '" + path + "'");
}

// The bytes `frames` frames take at most, uncompressed: the image (up to 3 channels), the 16-bit
// depth and the 16-bit object ids per pixel (PNG compresses them, noise textures hardly).
double EstimatedBytes(int frames, int width, int height) {
  return static_cast<double>(frames) * width * height * (3 + 2 + 2);
}

std::string Gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f GB", bytes / 1e9);
  return text;
}

// Refuses a dataset larger than the free space of the disk holding `out` (a --frames typo would
// otherwise fill it for hours), and says how large it may get.
void CheckDatasetFits(int frames, int width, int height, const output::OutputFolder& out) {
  const double needed = EstimatedBytes(frames, width, height);
  std::error_code error;
  const std::filesystem::space_info space = std::filesystem::space(out.directory(), error);
  if (!error && needed > static_cast<double>(space.available)) {
    throw config::UsageError(
        std::to_string(frames) + " frames of " + std::to_string(width) + "x" +
        std::to_string(height) + " need up to " + Gigabytes(needed) +
        " (image, 16-bit depth and object ids per frame, before PNG compression) but the disk "
        "holding '" +
        out.directory() + "' has " + Gigabytes(static_cast<double>(space.available)) +
        " free; render fewer --frames (trajectory.frames) or free space");
  }
  std::cout << "render: " << frames << " frames of " << width << "x" << height << ", up to "
            << Gigabytes(needed) << " uncompressed\n";
}

std::string FrameName(int index) {
  std::ostringstream name;
  name << std::setw(6) << std::setfill('0') << index << ".png";
  return name.str();
}

void RenderDataset(const RenderCommandOptions& options, output::OutputFolder& out) {
  // Ctrl-C / SIGTERM end the frame loop; the dataset is then closed with the frames so far.
  const output::InterruptionHandlers interruption;
  // Explicit flags win over --config files and --set items.
  CommonOptions common = options.common;
  if (!options.trajectory.empty())
    common.set_items.push_back("trajectory.kind=" + options.trajectory);
  if (options.frames > 0)
    common.set_items.push_back("trajectory.frames=" + std::to_string(options.frames));
  if (options.seed) common.set_items.push_back("seed=" + std::to_string(*options.seed));
  config::ConfigTree tree = config::ConfigTree::FromCommandLine(
      sim::BuiltinScenarioYaml(options.scenario), common.config_files, common.set_items);
  sim::Scenario scenario = sim::BuildScenario(sim::LoadScenarioParams(tree));
  const sim::ScenarioParams& params = scenario.params();
  PutEffectiveLeds(params, &tree);  // summary.json and scenario.yaml show the LEDs rendered
  const sim::ScenarioCamera& camera = scenario.render_camera();
  const sim::KinematicTrajectory trajectory(params.trajectory, scenario.T_WB_start(), params.seed);
  const int frame_count = params.trajectory.frames;
  const double duration_s = (frame_count - 1) / camera.rate_hz;
  CheckDatasetFits(frame_count, camera.model->width(), camera.model->height(), out);

  nlohmann::json& summary = out.summary();
  summary["command"] = "render";
  summary["inputs"] = {{"scenario", options.scenario},
                       {"trajectory", params.trajectory.kind},
                       {"camera", camera.name},
                       {"seed", params.seed}};
  summary["config"] = nlohmann::json::parse(tree.ToJson());
  nlohmann::json objects = nlohmann::json::array();
  for (const sim::SceneObject& object : scenario.scene().objects()) {
    objects.push_back({{"id", object.id}, {"name", object.name}});
  }
  summary["objects"] = objects;

  for (const char* folder : {"images", "depth", "masks"}) {
    std::filesystem::create_directories(out.Path(folder));
  }
  {
    std::ofstream yaml(out.Path("scenario.yaml"));
    yaml << tree.ToYaml() << "\n";
    if (!yaml) throw std::runtime_error("cannot write '" + out.Path("scenario.yaml") + "'");
  }
  perception::CameraCalibration calibration;
  calibration.camera = camera.model;
  calibration.name = camera.name;
  if (camera.T_BC) calibration.T_BC = *camera.T_BC;
  perception::SaveCameraCalibration(calibration, out.Path("calib.yaml"),
                                    perception::CalibrationFormat::kOpenCv);

  output::AtomicFile times(out.Path("images/times.txt"));
  times.stream() << std::setprecision(17);
  output::TumTrajectoryWriter groundtruth(out.Path("groundtruth.txt"));
  output::CsvWriter objects_csv(out.Path("objects.csv"),
                                {"t", "name", "tx", "ty", "tz", "qx", "qy", "qz", "qw"});
  output::ProgressBar progress("render", static_cast<std::size_t>(frame_count));
  output::HtmlReport report("aperture render: " + options.scenario);
  std::vector<double> t_values, x_values, y_values, z_values;
  double render_time_s = 0.0;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<int> key_frames{0, frame_count / 2, frame_count - 1};
  std::vector<std::pair<int, sim::CapturedFrame>> kept;

  sim::RayCaster caster;
  int frames_written = 0;
  for (int i = 0; i < frame_count && !output::InterruptionRequested(); ++i) {
    const double t_s = i / camera.rate_hz;
    const auto T_WB_at = [&](double t) {
      return trajectory.T_WB(duration_s > 0.0 ? t / duration_s : 0.0);
    };
    const Eigen::Isometry3d T_WB = T_WB_at(t_s);
    // Objects on the body are posed at mid-exposure (motion blur moves only the camera).
    scenario.SetVehiclePose(T_WB);
    const auto render_start = std::chrono::steady_clock::now();
    sim::CapturedFrame frame = camera.effects.Capture(
        caster, scenario.scene(), *camera.model, [&](double t) { return camera.T_WC(T_WB_at(t)); },
        t_s, i, camera.render);
    render_time_s +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();

    const std::string name = FrameName(i);
    WritePng(out.Path("images/" + name), frame.frame.image);
    WritePng(out.Path("depth/" + name), sim::DepthToMillimetres16U(frame.depth_C));
    WritePng(out.Path("masks/" + name), sim::ObjectIdsTo16U(frame.object_id));
    times.stream() << t_s << "\n";
    const Eigen::Isometry3d T_WC = camera.T_WC(T_WB);
    groundtruth.Write(t_s, T_WC);
    for (const sim::SceneObject& object : scenario.scene().objects()) {
      const Eigen::Quaterniond q(object.T_WO.linear());
      const Eigen::Vector3d& p = object.T_WO.translation();
      objects_csv.WriteCells({t_s, object.name, p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()});
    }
    t_values.push_back(t_s);
    x_values.push_back(T_WC.translation().x());
    y_values.push_back(T_WC.translation().y());
    z_values.push_back(T_WC.translation().z());
    if (std::find(key_frames.begin(), key_frames.end(), i) != key_frames.end()) {
      kept.emplace_back(i, std::move(frame));
    }
    frames_written = i + 1;
    progress.Update(static_cast<std::size_t>(frames_written));
  }
  progress.Finish();
  times.Commit();
  groundtruth.Close();
  objects_csv.Close();
  if (frames_written == 0) throw std::runtime_error("interrupted before the first frame");
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  summary["frames"] = frames_written;
  summary["frames_planned"] = frame_count;
  summary["estimated_bytes_uncompressed"] =
      EstimatedBytes(frames_written, camera.model->width(), camera.model->height());
  summary["image_size"] = {camera.model->width(), camera.model->height()};
  summary["timing"] = {{"render_s", render_time_s},
                       {"render_ms_per_frame", 1000.0 * render_time_s / frames_written},
                       {"total_s", wall_s},
                       {"frames_per_s", frames_written / wall_s},
                       {"render_frames_per_s", frames_written / render_time_s}};
  summary["outputs"] = {{"images", "images"},
                        {"times", "images/times.txt"},
                        {"depth", "depth"},
                        {"masks", "masks"},
                        {"groundtruth", "groundtruth.txt"},
                        {"objects", "objects.csv"},
                        {"calibration", "calib.yaml"},
                        {"config", "scenario.yaml"},
                        {"report", "report.html"}};

  report.AddSection("Summary");
  report.AddTable({{"scenario", options.scenario},
                   {"trajectory", params.trajectory.kind},
                   {"camera", camera.name + " (" + camera.model->model_name() + " " +
                                  std::to_string(camera.model->width()) + "x" +
                                  std::to_string(camera.model->height()) + ")"},
                   {"seed", params.seed},
                   {"frames", frames_written},
                   {"render [ms/frame]", 1000.0 * render_time_s / frames_written},
                   {"frames/s (with writing)", frames_written / wall_s}});
  report.AddSvg(output::SvgPlot({"Camera position p_WC", "t [s]", "[m]"})
                    .AddLine("x", t_values, x_values)
                    .AddLine("y", t_values, y_values)
                    .AddLine("z", t_values, z_values)
                    .Render());
  report.AddSection("Key frames");
  for (const auto& [index, frame] : kept) {
    const std::string label = "frame " + std::to_string(index);
    report.AddImage(frame.frame.image, label);
    report.AddImage(sim::DepthPreview(frame.depth_C, 15.0),
                    label + ": depth (bright = near, 0-15 m)");
    report.AddImage(sim::ObjectIdPreview(frame.object_id), label + ": object ids");
  }
  report.AddSection("Objects");
  report.AddTable(objects, "Object ids in masks/*.png");
  report.Write(out.Path("report.html"));
}

}  // namespace

void AddRenderCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* command =
      app.add_subcommand("render", "Render a dataset with ground truth from a scenario");
  command->add_option("scenario", options->scenario,
                      "Built-in scenario (REQUIRED): " + BuiltinScenarioList());
  command
      ->add_option("--trajectory", options->trajectory,
                   "hover | line | circle | scan | random (default: the scenario's)")
      ->check(CLI::IsMember({"hover", "line", "circle", "scan", "random"}));
  command->add_option("--frames", options->frames, "Frame count (default: the scenario's)")
      ->check(IntegerIn(1));
  AddSeedOption(command, &options->seed,
                "Randomization seed: textures, placements, noise (default: the scenario's)");
  AddCommonOptions(command, &options->common);
  command->callback([options, exit_code] {
    RequireBuiltinScenario(options->scenario);
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] { RenderDataset(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
