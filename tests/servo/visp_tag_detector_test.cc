// The ViSP tag detector adapter against the apriltag library's on one rendered frame: the same
// ids and corners (both shift to OpenCV pixel centres), and a clear error for the families
// Debian's ViSP build disables.
#include "servo/visp_tag_detector.h"

#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "perception/camera/pinhole_camera.h"
#include "perception/tags/apriltag_library_detector.h"
#include "sim/render/camera_effects.h"
#include "sim/scene/apriltag_object.h"
#include "sim/scene/scene.h"

namespace aperture::servo {
namespace {

cv::Mat RenderThreeTags(const std::string& family) {
  const perception::PinholeCamera camera(640, 480, {400.0, 400.0, 319.5, 239.5});
  sim::Scene scene;
  scene.AddObject({"ground", sim::GroundPlane{}, {}, Eigen::Isometry3d::Identity()});
  for (int id = 0; id < 3; ++id) {
    Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
    T_WO.translation() = Eigen::Vector3d(0.6 * id - 0.6, 0.1 * id, 0.01);
    T_WO.linear() = (Eigen::AngleAxisd(0.5 * id, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
    scene.AddObject(sim::MakeAprilTagObject(family, id + 3, 0.3, T_WO));
  }
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  T_WC.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T_WC.translation() = Eigen::Vector3d(0.0, 0.0, 2.0);
  sim::RayCaster caster;
  sim::CameraEffectsParams effects;
  effects.read_noise_sigma = 0.003;
  return sim::CameraEffects(effects)
      .Capture(
          caster, scene, camera, [&](double) { return T_WC; }, 0.0, 0)
      .frame.image;
}

TEST(VispTagDetector, FindsWhatTheAprilTagLibraryFindsAtTheSameCorners) {
  for (const char* family : {"tag36h11", "tag25h9"}) {
    const cv::Mat image = RenderThreeTags(family);
    perception::TagDetectorParams params;
    params.families = {family};
    params.quad_decimate = 1.0;
    const auto visp = CreateVispTagDetector(params)->Detect(image);
    const auto library = perception::AprilTagLibraryDetector(params).Detect(image);
    ASSERT_EQ(library.size(), 3u) << family;
    ASSERT_EQ(visp.size(), library.size()) << family;
    std::map<int, const perception::TagDetection*> by_id;
    for (const auto& detection : library) by_id[detection.id] = &detection;
    for (const auto& detection : visp) {
      ASSERT_TRUE(by_id.count(detection.id)) << family << " id " << detection.id;
      EXPECT_EQ(detection.family, family);
      for (int k = 0; k < 4; ++k) {
        EXPECT_LT((detection.corners_px[k] - by_id[detection.id]->corners_px[k]).norm(), 0.05)
            << family << " id " << detection.id << " corner " << k;
      }
    }
  }
}

TEST(VispTagDetector, RejectsFamiliesThisViSPBuildDisables) {
  perception::TagDetectorParams params;
  params.families = {"tagStandard41h12"};
  try {
    CreateVispTagDetector(params);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("apriltag.detector=apriltag"), std::string::npos);
  }
}

}  // namespace
}  // namespace aperture::servo
