// Camera calibration files (perception/camera/calibration_io.h): OpenCV FileStorage YAML, ROS
// camera_info YAML and Kalibr camchain, detected from the content as `aperture run --calib FILE`
// does. The loaders take a path (cv::FileStorage opens files), so the input goes to a file.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input_file.h"
#include "fuzz/yaml_exception_guard.h"
#include "perception/camera/calibration_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const aperture::fuzz::FuzzInputFile file(data, size, "calibration.yaml");
  try {
    aperture::perception::LoadCameraCalibration(file.path());
  } catch (const YAML::Exception& e) {
    aperture::fuzz::AbortOnLeakedYamlException(e);
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {
  }
  return 0;
}
