#include "perception/camera/camera_factory.h"

#include <stdexcept>

#include "perception/camera/equidistant_camera.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/camera/radtan_camera.h"

namespace aperture::perception {
namespace {

void CheckDistortionCount(const std::string& model_name, const Eigen::VectorXd& distortion,
                          int min_count, int max_count, const std::string& expected) {
  const int n = static_cast<int>(distortion.size());
  if (n < min_count || n > max_count) {
    throw std::invalid_argument("camera distortion: model '" + model_name + "' takes " + expected +
                                ", got " + std::to_string(n) + " coefficients");
  }
}

}  // namespace

std::unique_ptr<CameraModel> CreateCameraModel(const std::string& model_name, int width, int height,
                                               const Eigen::VectorXd& intrinsics,
                                               const Eigen::VectorXd& distortion) {
  if (intrinsics.size() != 4) {
    throw std::invalid_argument("camera intrinsics: expected 4 values [fx, fy, cx, cy], got " +
                                std::to_string(intrinsics.size()));
  }
  const PinholeIntrinsics k = PinholeIntrinsics::FromVector(intrinsics);
  if (model_name == "pinhole") {
    CheckDistortionCount(model_name, distortion, 0, 0, "no distortion coefficients");
    return std::make_unique<PinholeCamera>(width, height, k);
  }
  if (model_name == "radtan") {
    CheckDistortionCount(model_name, distortion, 4, 5, "4 or 5 coefficients k1 k2 p1 p2 [k3]");
    RadTanDistortion d{distortion[0], distortion[1], distortion[2], distortion[3], 0.0, false};
    if (distortion.size() == 5) {
      d.k3 = distortion[4];
      d.has_k3 = true;
    }
    return std::make_unique<RadTanCamera>(width, height, k, d);
  }
  if (model_name == "equidistant") {
    CheckDistortionCount(model_name, distortion, 4, 4, "4 coefficients k1 k2 k3 k4");
    return std::make_unique<EquidistantCamera>(
        width, height, k,
        EquidistantDistortion{distortion[0], distortion[1], distortion[2], distortion[3]});
  }
  throw std::invalid_argument("camera model: unknown model '" + model_name +
                              "'; use pinhole, radtan or equidistant");
}

}  // namespace aperture::perception
