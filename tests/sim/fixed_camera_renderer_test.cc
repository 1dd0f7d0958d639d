#include "sim/sitl/fixed_camera_renderer.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "perception/camera/pinhole_camera.h"
#include "sim/scenario/scenario.h"

namespace aperture::sim {
namespace {

Eigen::Isometry3d VehiclePose(const Eigen::Vector3d& p_W, double roll_rad, double yaw_rad) {
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.linear() = (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  T_WB.translation() = p_W;
  return T_WB;
}

class FixedCameraRendererTest : public ::testing::TestWithParam<int> {};

// The `led` scenario's ground camera (world-fixed 752 x 480 pinhole, textured ground, IR mode's
// dark scene) watching the vehicle body, arms and five LEDs move: every frame must equal the full
// render bit for bit, radiance and ground truth, while only a small rectangle is ray cast.
TEST_P(FixedCameraRendererTest, EqualsTheFullRenderWhileTheVehicleMoves) {
  Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig("led")));
  const ScenarioCamera& camera = scenario.render_camera();
  ASSERT_EQ(camera.model->model_name(), "pinhole");
  const Eigen::Isometry3d T_WC = camera.T_WC(scenario.T_WB_start());
  RenderOptions options = camera.render;
  options.supersampling = GetParam();
  options.ground_truth = true;
  options.reflectance_scale = 0.03f;  // IR mode (camera_effects.h)
  FixedCameraRenderer fixed(*camera.model, T_WC);
  RayCaster full_caster;
  // Start, then moves and tilts across the view, then a pose with LEDs near the image border.
  const Eigen::Isometry3d poses[] = {scenario.T_WB_start(), VehiclePose({0.1, 0.0, 2.0}, 0.1, 0.3),
                                     VehiclePose({-0.3, 0.2, 1.6}, -0.4, 1.0),
                                     VehiclePose({0.5, -0.3, 2.4}, 0.2, -2.0),
                                     VehiclePose({1.4, 0.6, 1.5}, 0.3, 0.5)};
  double largest_fraction = 0.0;
  for (size_t i = 0; i < std::size(poses); ++i) {
    scenario.SetVehiclePose(poses[i]);
    RenderOutput reused, full;
    fixed.Render(scenario.scene(), options, &reused);
    full_caster.Render(scenario.scene(), *camera.model, T_WC, options, &full);
    EXPECT_EQ(cv::norm(reused.radiance, full.radiance, cv::NORM_INF), 0.0) << "pose " << i;
    EXPECT_EQ(cv::norm(reused.depth_C, full.depth_C, cv::NORM_INF), 0.0) << "pose " << i;
    EXPECT_EQ(cv::countNonZero(reused.object_id != full.object_id), 0) << "pose " << i;
    // The vehicle body and an LED are in view, so the comparison covers them.
    EXPECT_GT(cv::countNonZero(full.object_id == scenario.scene().FindId("led_target")), 0);
    EXPECT_GT(cv::countNonZero(full.object_id == scenario.scene().FindId("led0")), 0);
    if (i > 0) largest_fraction = std::max(largest_fraction, fixed.last_render_fraction());
  }
  // Only a rectangle around the vehicle (a few % of the image at ~2 m) is ray cast.
  EXPECT_GT(largest_fraction, 0.0);
  EXPECT_LT(largest_fraction, 0.15);
  // The first frame's background is the whole scene; the second renders it without the vehicle.
  EXPECT_EQ(fixed.background_renders(), 2);
}

INSTANTIATE_TEST_SUITE_P(Supersampling, FixedCameraRendererTest, ::testing::Values(1, 2));

TEST(FixedCameraRendererStaticTest, AnObjectThatStartsMovingLeavesTheBackground) {
  Scene scene;
  scene.AddObject({"ground", GroundPlane{}, Material{}, Eigen::Isometry3d::Identity()});
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.translation() = Eigen::Vector3d(0.0, 0.0, 0.5);
  const int box = scene.AddObject({"box", Box{Eigen::Vector3d(0.3, 0.3, 0.3)}, Material{}, T_WO});
  const perception::PinholeCamera camera(160, 120,
                                         perception::PinholeIntrinsics{100, 100, 79.5, 59.5});
  Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();  // looking down from 3 m
  T_WC.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T_WC.translation() = Eigen::Vector3d(0.0, 0.0, 3.0);
  FixedCameraRenderer fixed(camera, T_WC);
  RayCaster full_caster;
  for (int frame = 0; frame < 4; ++frame) {
    if (frame >= 2) {  // the box moves from the third frame on
      T_WO.translation().x() += 0.2;
      scene.SetPose(box, T_WO);
    }
    RenderOutput reused;
    fixed.Render(scene, RenderOptions{}, &reused);
    const RenderOutput full = full_caster.Render(scene, camera, T_WC);
    EXPECT_EQ(cv::norm(reused.radiance, full.radiance, cv::NORM_INF), 0.0) << "frame " << frame;
  }
  EXPECT_EQ(fixed.background_renders(), 2);  // the whole scene, then without the box
}

}  // namespace
}  // namespace aperture::sim
