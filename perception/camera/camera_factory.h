#pragma once
// Builds a camera model from its name and parameter vectors, validating every field.
#include <Eigen/Core>
#include <memory>
#include <string>

#include "perception/camera/camera_model.h"

namespace aperture::perception {

// model_name: "pinhole" | "radtan" | "equidistant". intrinsics = [fx, fy, cx, cy] [px].
// distortion (OpenCV order): pinhole none; radtan k1 k2 p1 p2 [k3] (4 or 5); equidistant
// k1 k2 k3 k4 (4). Throws std::invalid_argument naming the field (model, width, height,
// intrinsics, fx, fy, cx, cy, distortion) and what is expected.
std::unique_ptr<CameraModel> CreateCameraModel(const std::string& model_name, int width, int height,
                                               const Eigen::VectorXd& intrinsics,
                                               const Eigen::VectorXd& distortion);

}  // namespace aperture::perception
