#pragma once
// Test support: the suites' standard pinhole camera, 752x480 px, f = 420 px, principal point at
// the image centre.
#include <memory>

#include "perception/camera/pinhole_camera.h"

namespace aperture::test_support {

inline std::shared_ptr<const perception::CameraModel> Pinhole752x480() {
  return std::make_shared<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{420.0, 420.0, 375.5, 239.5});
}

}  // namespace aperture::test_support
