// aperture calibrate: intrinsic calibration from a folder of target images.
//
//   aperture calibrate --images DIR --pattern circles:6x6:0.03 --model radtan --out OUT
//
// Writes OUT/calib.yaml (OpenCV FileStorage format, readable by --calib), OUT/summary.json with
// rms_px and per-image errors, OUT/per_image.csv and OUT/report.html.
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/command_support.h"
#include "apps/commands.h"
#include "output/csv_writer.h"
#include "output/html_report.h"
#include "output/svg_plot.h"
#include "perception/camera/calibration_io.h"
#include "perception/camera/camera_calibrator.h"
#include "perception/io/image_file_reader.h"
#include "perception/io/natural_sort.h"

namespace aperture::apps {
namespace {

struct CalibrateOptions {
  std::string out_dir;
  bool overwrite = false;
  std::string images_dir;
  std::string pattern;
  std::string model = "radtan";
};

std::vector<perception::CalibrationImage> ReadCalibrationImages(const std::string& folder) {
  if (!std::filesystem::is_directory(folder)) {
    throw std::runtime_error("calibration image folder '" + folder +
                             "' does not exist or is not a folder; pass --images DIR");
  }
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.is_regular_file() && perception::HasImageExtension(entry.path())) {
      names.push_back(entry.path().filename().string());
    }
  }
  if (names.empty()) {
    throw std::runtime_error("calibration image folder '" + folder +
                             "' holds no images (.png .jpg .pgm ...)");
  }
  perception::NaturalSort(names);
  std::vector<perception::CalibrationImage> images;
  for (const std::string& name : names) {
    images.push_back({name, perception::ReadImageFile(std::filesystem::path(folder) / name,
                                                      perception::ColorMode::kGray)});
  }
  return images;
}

void Calibrate(const CalibrateOptions& options, output::OutputFolder& out) {
  const perception::PatternSpec pattern = perception::ParsePatternSpec(options.pattern);
  const perception::CalibrationModel model = perception::ParseCalibrationModel(options.model);
  const std::vector<perception::CalibrationImage> images =
      ReadCalibrationImages(options.images_dir);
  nlohmann::json& summary = out.summary();
  summary["command"] = "calibrate";
  summary["inputs"] = {{"images", options.images_dir},
                       {"pattern", options.pattern},
                       {"model", options.model},
                       {"image_count", images.size()}};

  const perception::CameraCalibrationResult result =
      perception::CalibrateFromImages(images, pattern, model);
  output::CsvWriter csv(out.Path("per_image.csv"), {"image", "found", "rms_px"});
  nlohmann::json per_image = nlohmann::json::array();
  std::vector<double> errors_px;
  for (const auto& image : result.per_image) {
    csv.WriteCells({image.name, double(image.found), image.rms_px});
    per_image.push_back({{"image", image.name}, {"found", image.found}, {"rms_px", image.rms_px}});
    if (image.found) errors_px.push_back(image.rms_px);
  }
  csv.Close();
  summary["per_image"] = per_image;
  summary["images_used"] = result.images_used;
  if (result.status != perception::CameraCalibrationResult::Status::kOk) {
    throw std::runtime_error("calibration failed: " + result.message);
  }
  summary["rms_px"] = result.rms_px;

  perception::CameraCalibration calibration;
  calibration.camera = result.camera;
  const std::string calib_path = out.Path("calib.yaml");
  perception::SaveCameraCalibration(calibration, calib_path,
                                    perception::CalibrationFormat::kOpenCv);
  // Prove the file is usable before reporting success.
  perception::LoadCameraCalibration(calib_path);
  summary["outputs"] = {
      {"calibration", "calib.yaml"}, {"csv", "per_image.csv"}, {"report", "report.html"}};
  std::cout << result << "\ncalibration written to " << calib_path << "\n";

  output::HtmlReport report("aperture calibrate: " + options.images_dir);
  report.AddSection("Result");
  report.AddTable({{"model", options.model},
                   {"pattern", options.pattern},
                   {"images used", result.images_used},
                   {"rms [px]", result.rms_px}});
  report.AddTable(per_image, "Per-image reprojection error");
  report.AddSvg(output::SvgPlot::Histogram({"Per-image RMS reprojection error", "px", "images"},
                                           {{"images", errors_px}}));
  report.Write(out.Path("report.html"));
}

}  // namespace

void AddCalibrateCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<CalibrateOptions>();
  CLI::App* command = app.add_subcommand("calibrate", "Calibrate a camera from target images");
  command->add_option("--images", options->images_dir, "Folder of target images")->required();
  command
      ->add_option("--pattern", options->pattern,
                   "chessboard:COLSxROWS:SQUARE_M or circles:COLSxROWS:SPACING_M")
      ->required();
  command->add_option("--model", options->model, "radtan or fisheye")
      ->check(CLI::IsMember({"radtan", "fisheye"}));
  command->add_option("--out", options->out_dir, "Output folder (created if missing)")->required();
  AddOverwriteFlag(command, &options->overwrite);
  command->callback([options, exit_code] {
    output::OutputFolder out = OpenOutputFolder(options->out_dir, options->overwrite);
    output::RunAndWriteSummary(out, [&] { Calibrate(*options, out); });
    *exit_code = 0;
  });
}

}  // namespace aperture::apps
