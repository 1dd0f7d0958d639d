// The bench's LED target renderer with a body: the LEDs behind the body are not drawn, and
// OccludedLeds names exactly those.
#include "experiments/led/led_target_renderer.h"

#include <gtest/gtest.h>

#include <memory>

#include "perception/camera/pinhole_camera.h"

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

}  // namespace
}  // namespace aperture::experiments
