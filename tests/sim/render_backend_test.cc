// The renderer's two ray-object back ends (ray_caster.h RayBackend) give the same frames: the
// gap, gapflyt, tags and forest scenarios' render cameras at their start pose and settings, and
// a fisheye view of every primitive kind (sphere, cylinder, box, rectangles with polygon and
// ellipse holes, ground). Ids agree in >= 99.9 % of the pixels, depths within 1e-4 relative
// where they agree, and the radiance is the same up to the pixels an edge ray is decided
// differently on (float triangles in Embree): >= 99.9 % of the pixels equal to 1e-6, the mean
// absolute difference below 1e-4 (8-bit grey level: 1 / 255 = 3.9e-3).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "sim/render/embree_scene.h"
#include "sim/render/ray_caster.h"
#include "sim/scenario/scenario.h"
#include "tests/sim/render_test_util.h"

namespace aperture::sim {
namespace {

constexpr double kBackendMinEqualFraction = 0.999;
constexpr double kBackendDepthRelative = 1e-4;
constexpr double kBackendRadianceEqual = 1e-6;
constexpr double kBackendMeanRadianceDiff = 1e-4;

struct BackendComparison {
  int pixels = 0;
  int equal_ids = 0;
  int equal_radiance = 0;  // within kBackendRadianceEqual
  double mean_radiance_diff = 0.0;
  int depth_mismatches = 0;  // equal-id pixels whose depths differ by more than 1e-4 relative
  int sky_pixels = 0;        // both back ends, as a check that the frame is not all sky
};

BackendComparison CompareBackends(const Scene& scene, const perception::CameraModel& camera,
                                  const Eigen::Isometry3d& T_WC, RenderOptions options) {
  options.ground_truth = true;
  RayCaster ours(RayBackend::kTileCulling);
  RayCaster embree(RayBackend::kEmbree);
  const RenderOutput a = ours.Render(scene, camera, T_WC, options);
  const RenderOutput b = embree.Render(scene, camera, T_WC, options);
  BackendComparison c;
  const int channels = a.radiance.channels();
  c.pixels = a.radiance.rows * a.radiance.cols;
  for (int y = 0; y < a.radiance.rows; ++y) {
    for (int x = 0; x < a.radiance.cols; ++x) {
      const int id = a.object_id.at<int32_t>(y, x);
      if (id == b.object_id.at<int32_t>(y, x)) {
        ++c.equal_ids;
        const float da = a.depth_C.at<float>(y, x);
        const float db = b.depth_C.at<float>(y, x);
        if (id == 0) {
          ++c.sky_pixels;
        } else if (!(std::abs(da - db) <= kBackendDepthRelative * std::abs(da))) {
          ++c.depth_mismatches;
        }
      }
      double diff = 0.0;
      for (int ch = 0; ch < channels; ++ch) {
        diff = std::max(diff,
                        std::abs(static_cast<double>(a.radiance.ptr<float>(y)[x * channels + ch]) -
                                 b.radiance.ptr<float>(y)[x * channels + ch]));
      }
      if (diff <= kBackendRadianceEqual) ++c.equal_radiance;
      c.mean_radiance_diff += diff;
    }
  }
  c.mean_radiance_diff /= c.pixels;
  return c;
}

void ExpectEqualWithinNoise(const BackendComparison& c, const std::string& what) {
  EXPECT_GE(c.equal_ids, kBackendMinEqualFraction * c.pixels) << what;
  EXPECT_EQ(c.depth_mismatches, 0) << what;
  EXPECT_GE(c.equal_radiance, kBackendMinEqualFraction * c.pixels) << what;
  EXPECT_LT(c.mean_radiance_diff, kBackendMeanRadianceDiff) << what;
  std::printf(
      "%s: %d of %d pixels with other ids, %d with other radiance, mean |radiance "
      "difference| %.3g\n",
      what.c_str(), c.pixels - c.equal_ids, c.pixels, c.pixels - c.equal_radiance,
      c.mean_radiance_diff);
}

TEST(RenderBackend, EmbreeGivesTheSameScenarioFramesAsTileCulling) {
  if (!EmbreeAvailable()) GTEST_SKIP() << "built without Embree (APERTURE_EMBREE=OFF)";
  for (const std::string name : {"gap", "gapflyt", "tags", "forest"}) {
    const Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig(name)));
    const ScenarioCamera& camera = scenario.render_camera();
    const BackendComparison c = CompareBackends(scenario.scene(), *camera.model,
                                                camera.T_WC(scenario.T_WB_start()), camera.render);
    ExpectEqualWithinNoise(c, name);
    EXPECT_LT(c.sky_pixels, 0.9 * camera.model->width() * camera.model->height()) << name;
  }
}

TEST(RenderBackend, EmbreeGivesTheSameHitsOnEveryPrimitiveKind) {
  if (!EmbreeAvailable()) GTEST_SKIP() << "built without Embree (APERTURE_EMBREE=OFF)";
  Scene scene;
  ProceduralTextureParams texture;
  scene.AddObject({"ground", GroundPlane{}, {MakeGrassTexture(texture)}});
  scene.AddObject({"sphere", Sphere{0.6}, {}, testing::Pose({0, 0, 0}, {4.0, 1.5, 1.0})});
  scene.AddObject({"trunk", Cylinder{0.3, 2.5}, {}, testing::Pose({0, 0, 0}, {5.0, -1.5, 0.0})});
  scene.AddObject(
      {"crate", Box{{0.8, 0.5, 0.6}}, {}, testing::Pose({0.1, 0.2, 0.7}, {3.0, -0.6, 0.5})});
  // Walls facing the camera (z_O along +x_W): one with a triangular and one with an elliptic
  // hole, the second seen through the first.
  Eigen::Isometry3d T_W_wall = testing::LookAt({2.5, 0.0, 1.2}, Eigen::Vector3d::UnitX());
  Rectangle holed{{3.0, 2.0}, {{{-0.5, -0.4}, {0.6, -0.3}, {0.0, 0.5}}}, {}};
  scene.AddObject({"wall", holed, {MakeNewspaperTexture(texture)}, T_W_wall});
  Rectangle ellipse_holed{{6.0, 3.0}, {}, {EllipseHole{{0.3, 0.1}, {0.5, 0.3}, 0.4}}};
  T_W_wall.translation() = Eigen::Vector3d(7.0, 0.0, 1.5);
  scene.AddObject({"back", ellipse_holed, {MakeValueNoiseTexture(texture)}, T_W_wall});
  const auto camera = testing::MakeTestFisheye();
  RenderOptions options;
  options.supersampling = 2;
  options.color = true;
  const BackendComparison c =
      CompareBackends(scene, *camera, testing::LookAt({0.0, 0.1, 1.3}, {1.0, 0.05, -0.1}), options);
  ExpectEqualWithinNoise(c, "primitives");
  EXPECT_GT(c.sky_pixels, 0);
}

}  // namespace
}  // namespace aperture::sim
