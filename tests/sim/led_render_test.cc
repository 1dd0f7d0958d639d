#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "render_test_util.h"
#include "sim/render/camera_effects.h"
#include "sim/render/ray_caster.h"

namespace aperture::sim {
namespace {

using testing::Pose;

SceneObject MakeLed(const std::string& name, const Eigen::Vector3d& p_W, double radius_m,
                    double intensity) {
  SceneObject led;
  led.name = name;
  led.primitive = Led{radius_m, intensity, Rgb::Ones()};
  led.T_WO = Pose({0, 0, 0}, p_W);
  return led;
}

// Intensity-weighted centroid of an 8-bit image in a (2 r + 1)^2 window around px.
Eigen::Vector2d Centroid(const cv::Mat& image, const Eigen::Vector2d& px, int r, double* mass) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  *mass = 0.0;
  const int cx = static_cast<int>(std::lround(px.x()));
  const int cy = static_cast<int>(std::lround(px.y()));
  for (int y = std::max(0, cy - r); y <= std::min(image.rows - 1, cy + r); ++y) {
    for (int x = std::max(0, cx - r); x <= std::min(image.cols - 1, cx + r); ++x) {
      const double v = image.type() == CV_8UC1 ? image.at<uint8_t>(y, x) : image.at<float>(y, x);
      sum += v * Eigen::Vector2d(x, y);
      *mass += v;
    }
  }
  return sum / *mass;
}

class LedRenderTest : public ::testing::TestWithParam<bool> {
 protected:
  std::unique_ptr<perception::CameraModel> camera_ =
      GetParam() ? testing::MakeTestFisheye() : testing::MakeTestPinhole();
};

TEST_P(LedRenderTest, BlobCentroidsAreTheProjectedEmitters) {
  const bool fisheye = GetParam();
  // Camera frame = world frame. Fisheye LEDs reach 56, 76 and 95 deg off the axis.
  const std::vector<Eigen::Vector3d> p_C =
      fisheye ? std::vector<Eigen::Vector3d>{{0.0, 0.0, 1.5},
                                             {0.3, -0.25, 2.0},
                                             {1.5, 0.2, 1.0},
                                             {-2.0, -0.3, 0.5},
                                             {2.0, 0.0, -0.17}}
              : std::vector<Eigen::Vector3d>{{0.0, 0.0, 1.5},
                                             {0.4, -0.3, 2.0},
                                             {-0.7, 0.35, 1.8},
                                             {0.9, 0.5, 2.5},
                                             {-0.253, -0.507, 3.1}};
  // Resolved emitters (radius 2 cm): sigma = half the projected radius, the peak is
  // intensity / (2 pi sigma^2) whatever the distance; aim at a peak of ~0.6 (unsaturated).
  const double f = fisheye ? 215.0 : 420.0;
  const double radius = 0.02;
  const double intensity = 0.6 * 2.0 * M_PI * std::pow(0.5 * radius * f, 2);
  Scene scene;
  for (size_t i = 0; i < p_C.size(); ++i) {
    scene.AddObject(MakeLed("led" + std::to_string(i), p_C[i], radius, intensity));
  }
  CameraEffectsParams params;
  params.infrared = true;
  params.infrared_reflectance_scale = 0.0f;  // black background: the centroid sees only LEDs
  RayCaster caster;
  const CapturedFrame captured = CameraEffects(params).Capture(
      caster, scene, *camera_, [](double) { return Eigen::Isometry3d::Identity(); }, 0.0, 0);
  double worst = 0.0;
  for (size_t i = 0; i < p_C.size(); ++i) {
    Eigen::Vector2d px;
    ASSERT_TRUE(camera_->Project(p_C[i], &px));
    ASSERT_TRUE(camera_->IsInImage(px, 12.0));
    double mass;
    const Eigen::Vector2d centroid = Centroid(captured.frame.image, px, 10, &mass);
    EXPECT_GT(mass, 50.0);
    worst = std::max(worst, (centroid - px).norm());
    EXPECT_EQ(captured.object_id.at<int32_t>(static_cast<int>(std::lround(px.y())),
                                             static_cast<int>(std::lround(px.x()))),
              static_cast<int>(i) + 1);
    double peak;
    cv::minMaxLoc(captured.frame.image(
                      cv::Rect(static_cast<int>(px.x()) - 3, static_cast<int>(px.y()) - 3, 7, 7)),
                  nullptr, &peak);
    EXPECT_LT(peak, 255.0);  // unsaturated, else clipping would bias the centroid
  }
  std::printf("max LED centroid error (%s): %.4f px\n", camera_->model_name().c_str(), worst);
  // Brief: within 0.3 px. Residual sources: 8-bit rounding (<= 0.5 / 255 per pixel) and the
  // blob tail outside the window (~exp(-12)); both far below 0.3 px.
  EXPECT_LT(worst, 0.3);
}

INSTANTIATE_TEST_SUITE_P(PinholeAndFisheye, LedRenderTest, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "Fisheye" : "Pinhole"; });

// The radiance summed over an 8 px window around p_C's projection (an LED blob's energy).
double BlobEnergy(const RenderOutput& out, const perception::CameraModel& camera,
                  const Eigen::Vector3d& p_C) {
  Eigen::Vector2d px;
  EXPECT_TRUE(camera.Project(p_C, &px));
  double mass;
  Centroid(out.radiance, px, 8, &mass);
  return mass;
}

TEST(LedRenderFalloffTest, EnergyFallsWithInverseSquareDistanceAndOccludersHideLeds) {
  const auto camera = testing::MakeTestPinhole();
  Scene scene;
  scene.sky.zenith_color = scene.sky.horizon_color = scene.sky.ground_color = Rgb::Zero();
  // Unresolved 1 mm emitters at 2 m and 4 m; a third one hidden behind a small plate.
  scene.AddObject(MakeLed("near", {-0.3, 0.0, 2.0}, 0.001, 20.0));
  scene.AddObject(MakeLed("far", {0.6, 0.0, 4.0}, 0.001, 20.0));
  scene.AddObject(MakeLed("hidden", {0.0, 0.4, 3.0}, 0.001, 20.0));
  scene.AddObject({"plate", Rectangle{{0.2, 0.2}, {}, {}}, {}, Pose({0, 0, 0}, {0.0, 0.2, 1.5})});
  RayCaster caster;
  const RenderOutput out = caster.Render(scene, *camera, Eigen::Isometry3d::Identity());
  const auto energy = [&](const Eigen::Vector3d& p) { return BlobEnergy(out, *camera, p); };
  const double near = energy({-0.3, 0.0, 2.0});
  const double far = energy({0.6, 0.0, 4.0});
  const double near_distance = Eigen::Vector3d(-0.3, 0.0, 2.0).norm();
  const double far_distance = Eigen::Vector3d(0.6, 0.0, 4.0).norm();
  EXPECT_NEAR(near, 20.0 / (near_distance * near_distance), 1e-4);  // exact pixel integrals
  EXPECT_NEAR(far / near, std::pow(near_distance / far_distance, 2), 1e-4);
  // The hidden LED's window shows the unlit plate only (ambient-lit grey, no LED energy).
  Eigen::Vector2d px_hidden;
  ASSERT_TRUE(camera->Project({0.0, 0.4, 3.0}, &px_hidden));
  EXPECT_EQ(
      out.object_id.at<int32_t>(static_cast<int>(px_hidden.y()), static_cast<int>(px_hidden.x())),
      scene.FindId("plate"));
  double hidden_peak;
  cv::minMaxLoc(out.radiance(cv::Rect(static_cast<int>(px_hidden.x()) - 4,
                                      static_cast<int>(px_hidden.y()) - 4, 9, 9)),
                nullptr, &hidden_peak);
  EXPECT_LT(hidden_peak, 0.7f + 1e-6);  // plate albedo 0.7 at most fully lit
}

// A Lambertian emitter (radiation_exponent 1) seen 60 deg off its axis shows half the energy of
// one seen on its axis at the same distance, and nothing from behind.
TEST(LedRenderFalloffTest, RadiationPatternScalesTheEnergyByTheAngleOffTheAxis) {
  const auto camera = testing::MakeTestPinhole();
  Scene scene;
  scene.sky.zenith_color = scene.sky.horizon_color = scene.sky.ground_color = Rgb::Zero();
  const Eigen::Vector3d p_on(-0.4, 0.0, 2.0), p_off(0.4, 0.0, 2.0), p_behind(0.0, 0.4, 2.0);
  // Axes: towards the camera; 60 deg off the direction to the camera; away from the camera.
  const auto facing = [](const Eigen::Vector3d& p, double extra_angle_rad) {
    const Eigen::Vector3d to_camera = -p.normalized();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d axis =
        Eigen::AngleAxisd(extra_angle_rad, Eigen::Vector3d::UnitY()) * to_camera;
    T.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).matrix();
    T.translation() = p;
    return T;
  };
  const double pi = 3.14159265358979323846;
  int i = 0;
  for (const auto& [p, angle] : {std::pair{p_on, 0.0}, {p_off, pi / 3.0}, {p_behind, pi}}) {
    SceneObject led = MakeLed("led" + std::to_string(i++), p, 0.001, 20.0);
    std::get<Led>(led.primitive).radiation_exponent = 1.0;
    led.T_WO = facing(p, angle);
    scene.AddObject(led);
  }
  RayCaster caster;
  const RenderOutput out = caster.Render(scene, *camera, Eigen::Isometry3d::Identity());
  const auto energy = [&](const Eigen::Vector3d& p) { return BlobEnergy(out, *camera, p); };
  EXPECT_NEAR(energy(p_on), 20.0 / p_on.squaredNorm(), 1e-4);
  EXPECT_NEAR(energy(p_off) / energy(p_on), 0.5, 1e-3);
  EXPECT_LT(energy(p_behind), 1e-9);
}

TEST(LedRenderFalloffTest, InfraredModeDarkensTheSceneButNotTheLeds) {
  const auto camera = testing::MakeTestPinhole();
  Scene scene;
  scene.AddObject({"wall", Rectangle{{10.0, 10.0}, {}, {}}, {}, Pose({0, 0, 0}, {0.0, 0.0, 5.0})});
  // Projects onto the centre of pixel (375, 239): p_C = ((375 - cx) / f, (239 - cy) / f, 1) * 2.
  scene.AddObject(MakeLed("led", {-0.5 / 420.0 * 2.0, -0.5 / 420.0 * 2.0, 2.0}, 0.005, 10.0));
  RayCaster caster;
  auto capture = [&](bool infrared) {
    CameraEffectsParams params;
    params.infrared = infrared;
    params.infrared_reflectance_scale = 0.1f;
    return CameraEffects(params).Capture(
        caster, scene, *camera, [](double) { return Eigen::Isometry3d::Identity(); }, 0.0, 0);
  };
  const CapturedFrame normal = capture(false);
  const CapturedFrame infrared = capture(true);
  const float wall_normal = normal.radiance.at<float>(50, 50);
  const float wall_ir = infrared.radiance.at<float>(50, 50);
  EXPECT_NEAR(wall_ir, 0.1f * wall_normal, 1e-6);
  // At the LED, IR radiance = normal radiance - 0.9 * wall radiance (the LED term is unchanged).
  EXPECT_NEAR(infrared.radiance.at<float>(239, 375),
              normal.radiance.at<float>(239, 375) - 0.9f * wall_normal, 1e-5);
  EXPECT_GT(infrared.radiance.at<float>(239, 375), 10.0f * wall_ir);  // emitters dominate
}

}  // namespace
}  // namespace aperture::sim
