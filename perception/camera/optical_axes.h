#pragma once
// The rotation R_PO of an optical frame O (OpenCV axes: x right, y down, z forward) looking along
// x of a z-up frame P: z_O = x_P, x_O = -y_P, y_O = -z_P. It is a forward camera's R_BC, and the
// pose of a pattern (gap, panel) standing upright that a viewer looking along +x_P sees unmirrored.
#include <Eigen/Core>

namespace aperture::perception {

inline Eigen::Matrix3d OpticalAxesAlongX() {
  Eigen::Matrix3d R_PO;
  R_PO << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return R_PO;
}

}  // namespace aperture::perception
