// The bench's LED target renderer with a body: the LEDs behind the body are not drawn, and
// OccludedLeds names exactly those; with calibration errors the blobs move as the erroneous
// camera and LED positions project them.
#include "experiments/led/led_target_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <stdexcept>

#include "perception/camera/equidistant_camera.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/led/led_detector.h"

namespace aperture::experiments {
namespace {

TEST(LedTargetRendererTest, TheBodyHidesTheLedsBehindItAndOnlyThose) {
  // LED 0 sits 2 cm above the top of a 16 x 12 x 6 cm body and 1 cm beyond its +x side: a
  // camera 1.5 m below (looking along +z_T) sees it past the edge, but with the target turned
  // by -30 deg about y_T the camera lies towards -x and the body's top is in the way. The
  // others stick out beyond the body's sides or hang below it: always visible.
  const perception::LedConfiguration configuration({{0.09, 0.0, 0.05},
                                                    {0.12, 0.01, 0.0},
                                                    {-0.02, 0.11, 0.0},
                                                    {-0.10, -0.06, -0.04},
                                                    {0.03, -0.09, -0.05}},
                                                   "test target");
  const auto camera = std::make_shared<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{376.0, 376.0, 375.5, 239.5});
  LedTargetRenderParams params;
  params.body_size_m = Eigen::Vector3d(0.16, 0.12, 0.06);
  params.effects.read_noise_sigma = 0.0;
  LedTargetRenderer renderer(configuration, camera, params);
  for (const double tilt_deg : {0.0, -30.0}) {
    Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
    T_CT.linear() =
        Eigen::AngleAxisd(tilt_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T_CT.translation() = Eigen::Vector3d(0.0, 0.0, 1.5);
    const std::vector<int> occluded = renderer.OccludedLeds(T_CT);
    EXPECT_EQ(occluded, tilt_deg == 0.0 ? std::vector<int>{} : std::vector<int>{0})
        << tilt_deg << " deg";
    const cv::Mat image =
        renderer.Render([&](double) { return T_CT; }, 0.0, tilt_deg == 0.0 ? 0 : 1);
    for (int led = 0; led < configuration.size(); ++led) {
      Eigen::Vector2d px;
      ASSERT_TRUE(camera->Project(T_CT * configuration.p_T()[led], &px));
      const int gray = image.at<std::uint8_t>(static_cast<int>(std::lround(px.y())),
                                              static_cast<int>(std::lround(px.x())));
      // A drawn LED saturates its centre pixel at 1.5 m; the dark body and ceiling stay far
      // below the detector's 120 threshold.
      const bool hidden = tilt_deg != 0.0 && led == 0;
      if (hidden) {
        EXPECT_LT(gray, 60) << "LED " << led << " at " << tilt_deg << " deg";
      } else {
        EXPECT_GT(gray, 200) << "LED " << led << " at " << tilt_deg << " deg";
      }
    }
  }
}

// Issue 21's radiation pattern: Lambertian LEDs facing -z_T light the camera on that side and
// are dark from behind the target.
TEST(LedTargetRendererTest, WideAngleLedsFaceTheCamerasSideOfTheTarget) {
  const perception::LedConfiguration configuration = perception::LedConfiguration::Default();
  const auto camera = std::make_shared<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{376.0, 376.0, 375.5, 239.5});
  LedTargetRenderParams params;
  params.led_radiation_exponent = 1.0;
  params.effects.read_noise_sigma = 0.0;
  LedTargetRenderer renderer(configuration, camera, params);
  for (const double turn_deg : {0.0, 180.0}) {
    Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
    T_CT.linear() =
        Eigen::AngleAxisd(turn_deg * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
    T_CT.translation() = Eigen::Vector3d(0.0, 0.0, 1.5);
    const cv::Mat image = renderer.Render([&](double) { return T_CT; }, 0.0, 0);
    for (int led = 0; led < configuration.size(); ++led) {
      Eigen::Vector2d px;
      ASSERT_TRUE(camera->Project(T_CT * configuration.p_T()[led], &px));
      const int gray = image.at<std::uint8_t>(static_cast<int>(std::lround(px.y())),
                                              static_cast<int>(std::lround(px.x())));
      if (turn_deg == 0.0) {
        EXPECT_GT(gray, 200) << "LED " << led << " seen from its front";
      } else {
        EXPECT_LT(gray, 60) << "LED " << led << " seen from behind";
      }
    }
  }
}

// Issue 21's calibration-level errors: the image shows the LEDs where the erroneous intrinsics
// and displaced LEDs put them, not where the nominal camera and configuration (the tracker's)
// project them; the nominal camera stays the renderer's camera().
TEST(LedTargetRendererTest, CalibrationErrorsMoveTheBlobsAsTheErroneousModelProjects) {
  const perception::LedConfiguration configuration = perception::LedConfiguration::Default();
  const auto camera = std::make_shared<perception::PinholeCamera>(
      752, 480, perception::PinholeIntrinsics{376.0, 376.0, 375.5, 239.5});
  LedTargetRenderParams params;
  params.effects.read_noise_sigma = 0.0;
  params.effects.full_well_electrons = 0.0;
  params.calibration_error.focal_length_error = 0.02;
  params.calibration_error.principal_point_error_px = Eigen::Vector2d(3.0, -2.0);
  params.calibration_error.led_position_error_m = 0.001;
  LedTargetRenderer renderer(configuration, camera, params);
  EXPECT_EQ(&renderer.camera(), camera.get());
  const Eigen::Vector4d k = renderer.rendering_camera().intrinsics();
  EXPECT_DOUBLE_EQ(k[0], 376.0 * 1.02);
  EXPECT_DOUBLE_EQ(k[1], 376.0 * 1.02);
  EXPECT_DOUBLE_EQ(k[2], 378.5);
  EXPECT_DOUBLE_EQ(k[3], 237.5);
  for (int led = 0; led < configuration.size(); ++led) {
    EXPECT_NEAR((renderer.rendered_configuration().p_T()[led] - configuration.p_T()[led]).norm(),
                0.001, 1e-12)
        << "LED " << led;
  }
  Eigen::Isometry3d T_CT = Eigen::Isometry3d::Identity();
  T_CT.translation() = Eigen::Vector3d(0.3, 0.2, 1.0);
  const cv::Mat image = renderer.Render([&](double) { return T_CT; }, 0.0, 0);
  perception::LedDetector detector;
  const std::vector<perception::LedDetection> detections =
      detector.Detect(image, *camera).detections;
  ASSERT_EQ(detections.size(), static_cast<std::size_t>(configuration.size()));
  for (int led = 0; led < configuration.size(); ++led) {
    Eigen::Vector2d px_rendered, px_nominal;
    ASSERT_TRUE(renderer.rendering_camera().Project(
        T_CT * renderer.rendered_configuration().p_T()[led], &px_rendered));
    ASSERT_TRUE(camera->Project(T_CT * configuration.p_T()[led], &px_nominal));
    double nearest = std::numeric_limits<double>::infinity();
    for (const perception::LedDetection& d : detections) {
      nearest = std::min(nearest, (d.px - px_rendered).norm());
    }
    // The blob sits on the erroneous projection (centroid within 0.3 px) while the nominal one
    // is off by the 2 % focal error at ~100-200 px from the centre plus the principal point.
    EXPECT_LT(nearest, 0.3) << "LED " << led;
    EXPECT_GT((px_rendered - px_nominal).norm(), 3.0) << "LED " << led;
  }
}

TEST(LedTargetRendererTest, IntrinsicsErrorsNeedAPinholeCamera) {
  const auto camera = std::make_shared<perception::EquidistantCamera>(
      752, 480, perception::PinholeIntrinsics{376.0, 376.0, 375.5, 239.5},
      perception::EquidistantDistortion{});
  LedTargetRenderParams params;
  params.calibration_error.focal_length_error = 0.005;
  EXPECT_THROW(LedTargetRenderer(perception::LedConfiguration::Default(), camera, params),
               std::invalid_argument);
  params.calibration_error.focal_length_error = 0.0;
  params.calibration_error.led_position_error_m = 0.001;  // LED errors alone: any camera
  EXPECT_NO_THROW(LedTargetRenderer(perception::LedConfiguration::Default(), camera, params));
}

}  // namespace
}  // namespace aperture::experiments
