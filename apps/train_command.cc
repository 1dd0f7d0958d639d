// aperture train mono_depth: the per-patch depth classifier of seed 003 Sec. III-A from folders
// written by `aperture render` (colour images + 16-bit depth), optionally scored on held-out
// folders (Table I: E_ln, E_relative).
//
//   aperture train mono_depth --data D [--data D2 ...] [--eval E ...] [--set svm_c=0.5] --out OUT
//
// Writes OUT/mono_depth.model (load it with `--set mono_depth.model=OUT/mono_depth.model`, or copy
// it to perception/mono_depth/models/forest_mono_depth.model to ship it), OUT/summary.json
// (training set, per-label counts, training accuracy, held-out Table I errors, feature timing),
// OUT/eval.csv (per held-out frame errors) and OUT/report.html.
#include <chrono>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "output/csv_writer.h"
#include "output/html_report.h"
#include "output/progress_bar.h"
#include "perception/mono_depth/depth_errors.h"
#include "perception/mono_depth/mono_depth_estimator.h"
#include "perception/mono_depth/mono_depth_train_params_io.h"
#include "perception/mono_depth/rendered_depth_folder.h"

namespace aperture::apps {
namespace {

struct TrainOptions {
  CommonOptions common;
  std::vector<std::string> data;
  std::vector<std::string> eval;
};

cv::Mat ReadImage(const std::filesystem::path& path, int flags) {
  cv::Mat image = cv::imread(path.string(), flags);
  if (image.empty()) throw std::invalid_argument("cannot read image '" + path.string() + "'");
  return image;
}

std::vector<perception::ImageDepthPair> ListAll(const std::vector<std::string>& folders) {
  std::vector<perception::ImageDepthPair> pairs;
  for (const std::string& folder : folders) {
    for (auto& pair : perception::ListRenderedDepthFrames(folder)) pairs.push_back(pair);
  }
  return pairs;
}

// Table I on held-out frames; per-frame rows in eval.csv.
nlohmann::json Evaluate(const perception::MonoDepthModel& model,
                        const std::vector<perception::ImageDepthPair>& frames,
                        output::OutputFolder& out) {
  perception::MonoDepthEstimator estimator(model);
  output::CsvWriter csv(out.Path("eval.csv"),
                        {"frame", "patches", "e_ln", "e_relative", "estimate_ms"});
  output::ProgressBar progress("eval", frames.size());
  perception::DepthErrors total;
  std::vector<double> times_ms;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const cv::Mat bgr = ReadImage(frames[i].image, cv::IMREAD_COLOR);
    const cv::Mat depth_mm = ReadImage(frames[i].depth, cv::IMREAD_UNCHANGED);
    const auto start = std::chrono::steady_clock::now();
    const perception::MonoDepthEstimate estimate = estimator.Estimate(bgr);
    times_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    const perception::DepthErrors errors = perception::CompareDepth(
        estimate.depth_m, perception::PatchDepthFromMillimetres(depth_mm, estimate.grid),
        model.labels().MinDepth(), model.labels().MaxDepth());
    total += errors;
    csv.WriteRow({double(i), double(errors.patches), errors.MeanLn(), errors.MeanRelative(),
                  times_ms.back()});
    progress.Update(i + 1);
  }
  progress.Finish();
  csv.Close();
  std::sort(times_ms.begin(), times_ms.end());
  return {{"frames", frames.size()},
          {"patches", total.patches},
          {"e_ln", total.MeanLn()},
          {"e_relative", total.MeanRelative()},
          {"estimate_median_ms", times_ms[times_ms.size() / 2]},
          {"csv", "eval.csv"}};
}

void TrainMonoDepth(const TrainOptions& options, output::OutputFolder& out) {
  const config::ConfigTree tree = LoadConfig(options.common, "");
  perception::MonoDepthTrainParams params;
  config::ParamReader root = tree.Reader();
  perception::LoadParams(root, &params);

  const std::vector<perception::ImageDepthPair> train_frames = ListAll(options.data);
  const std::vector<perception::ImageDepthPair> eval_frames = ListAll(options.eval);
  nlohmann::json& summary = out.summary();
  summary["command"] = "train mono_depth";
  summary["inputs"] = {{"data", options.data}, {"eval", options.eval}};
  summary["config"] = nlohmann::json::parse(tree.ToJson());

  perception::MonoDepthTrainer trainer(params);
  output::ProgressBar progress("features", train_frames.size());
  for (std::size_t i = 0; i < train_frames.size(); ++i) {
    trainer.AddFrame(ReadImage(train_frames[i].image, cv::IMREAD_COLOR),
                     ReadImage(train_frames[i].depth, cv::IMREAD_UNCHANGED));
    progress.Update(i + 1);
  }
  progress.Finish();
  perception::MonoDepthTrainingReport report;
  const perception::MonoDepthModel model = trainer.Train(&report);
  model.Save(out.Path("mono_depth.model"));
  summary["training"] = {{"frames", report.frames},
                         {"patches", report.patches},
                         {"patches_per_label", report.patches_per_label},
                         {"label_edges_m", model.labels().Edges()},
                         {"accuracy", report.training_accuracy},
                         {"liblinear_time_s", report.train_time_s}};
  output::HtmlReport html("aperture train mono_depth");
  if (!eval_frames.empty()) {
    summary["eval"] = Evaluate(model, eval_frames, out);
    // One held-out frame with its estimate, for a look.
    perception::MonoDepthEstimator estimator(model);
    const cv::Mat bgr = ReadImage(eval_frames.front().image, cv::IMREAD_COLOR);
    html.AddImage(bgr, "held-out frame " + eval_frames.front().image.string());
    cv::Mat preview;
    perception::DepthImageMillimetres(estimator.Estimate(bgr), bgr.size())
        .convertTo(preview, CV_8U, -255.0 / 20000.0, 255.0);
    html.AddImage(preview, "estimated depth (bright = near, 0-20 m)");
  }
  summary["outputs"] = {{"model", "mono_depth.model"}, {"report", "report.html"}};
  html.Write(out.Path("report.html"));
}

}  // namespace

void AddTrainCommand(CLI::App& app, int* exit_code) {
  CLI::App* train = app.add_subcommand("train", "Train a learned perception model");
  train->require_subcommand(1);
  auto options = std::make_shared<TrainOptions>();
  CLI::App* command = train->add_subcommand(
      "mono_depth", "Per-patch monocular depth SVM (seed 003) from `aperture render` folders");
  command
      ->add_option("--data", options->data,
                   "Training folder(s) written by aperture render (images/ + depth/)")
      ->required();
  command->add_option("--eval", options->eval,
                      "Held-out folder(s) for the Table I errors (other seeds than --data)");
  AddCommonOptions(command, &options->common);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->common);
    output::RunAndWriteSummary(out, [&] { TrainMonoDepth(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
