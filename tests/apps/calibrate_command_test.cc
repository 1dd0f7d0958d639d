// `aperture calibrate` on the real circle-grid photos Debian's visp-images-data ships.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "perception/camera/calibration_io.h"
#include "tests/apps/cli_runner.h"

namespace aperture::apps::testing {
namespace {

namespace fs = std::filesystem;

// Where visp-images-data installs its calibration photos (a Debian package path).
const fs::path kVispCalibration = "/usr/share/visp-images-data/ViSP-images/calibration";

TEST(CalibrateCommand, CircleGridPhotosCalibrateBelowHalfAPixelAndLoadBack) {
  if (!fs::exists(kVispCalibration / "grid36-01.pgm")) {
    GTEST_SKIP() << "visp-images-data is not installed (scripts/install-deps.sh installs it)";
  }
  TempFolder temp("calibrate");
  const fs::path images = fs::path(temp.path()) / "images";
  fs::create_directories(images);
  for (int i = 1; i <= 4; ++i) {
    const std::string name = "grid36-0" + std::to_string(i) + ".pgm";
    fs::copy_file(kVispCalibration / name, images / name);
  }
  const fs::path out = fs::path(temp.path()) / "out";
  // ViSP's grid: 6x6 circles, 3 cm apart (its calibration example's config).
  const CommandResult result = RunAperture("calibrate --images " + images.string() +
                                           " --pattern circles:6x6:0.03 --model radtan --out " +
                                           out.string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream file(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(file);
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_LT(summary["rms_px"].get<double>(), 0.5);
  EXPECT_EQ(summary["images_used"], 4);
  ASSERT_EQ(summary["per_image"].size(), 4u);
  for (const auto& image : summary["per_image"]) EXPECT_LT(image["rms_px"].get<double>(), 0.5);
  const perception::CameraCalibration calibration =
      perception::LoadCameraCalibration((out / "calib.yaml").string());
  EXPECT_EQ(calibration.camera->width(), 640);  // the photos are 640x480
}

TEST(CalibrateCommand, BadPatternSpecAndMissingFolderFail) {
  TempFolder temp("calibrate-bad");
  const CommandResult bad_pattern = RunAperture("calibrate --images " + temp.path() +
                                                " --pattern hexagons:3x3:1 --out " + temp.path() +
                                                "/out");
  EXPECT_NE(bad_pattern.exit_code, 0);
  EXPECT_NE(bad_pattern.output.find("hexagons"), std::string::npos) << bad_pattern.output;
  const CommandResult missing = RunAperture("calibrate --images " + temp.path() +
                                            "/none --pattern circles:6x6:0.03 --out " +
                                            temp.path() + "/out2");
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("none"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace aperture::apps::testing
