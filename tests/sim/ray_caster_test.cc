#include "sim/render/ray_caster.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>

#include "render_test_util.h"
#include "sim/render/camera_effects.h"

namespace aperture::sim {
namespace {

using testing::LookAt;
using testing::Pose;

// A tilted wall (plane x_W = 3 + 0.3 y_W) and a ground plane, seen by the camera at the origin.
struct PlaneScene {
  Scene scene;
  Eigen::Vector3d wall_n_W = Eigen::Vector3d(1.0, -0.3, 0.0).normalized();
  Eigen::Vector3d wall_p_W = Eigen::Vector3d(3.0, 0.0, 0.0);
  Eigen::Vector3d ground_n_W = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d ground_p_W = Eigen::Vector3d(0.0, 0.0, -1.2);
  int wall_id = 0;
  int ground_id = 0;

  PlaneScene() {
    Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
    // z_O along the wall normal, y_O down, x_O horizontal: the 6 m side is horizontal.
    T_WO.linear().col(2) = wall_n_W;
    T_WO.linear().col(1) = -Eigen::Vector3d::UnitZ();
    T_WO.linear().col(0) = T_WO.linear().col(1).cross(wall_n_W);
    T_WO.translation() = wall_p_W;
    wall_id = scene.AddObject({"wall", Rectangle{{6.0, 2.0}, {}, {}}, {}, T_WO});
    ground_id = scene.AddObject({"ground", GroundPlane{}, {}, Pose({0, 0, 0}, ground_p_W)});
  }
};

class RayCasterCameraTest : public ::testing::TestWithParam<bool> {
 protected:
  std::unique_ptr<perception::CameraModel> camera_ =
      GetParam() ? testing::MakeTestFisheye() : testing::MakeTestPinhole();
};

TEST_P(RayCasterCameraTest, DepthAndIdsEqualAnalyticRayPlaneIntersections) {
  PlaneScene s;
  const Eigen::Isometry3d T_WC = Pose({0.05, -0.1, 0.02}, {0.0, 0.0, 0.0}) *
                                 LookAt(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX());
  RayCaster caster;
  const RenderOutput out = caster.Render(s.scene, *camera_, T_WC);
  int wall = 0, ground = 0, sky = 0;
  double worst_relative = 0.0;
  for (int y = 0; y < camera_->height(); y += 3) {
    for (int x = 0; x < camera_->width(); x += 3) {
      const Eigen::Vector3d d_C = camera_->Unproject({double(x), double(y)}).normalized();
      const Eigen::Vector3d d_W = T_WC.linear() * d_C;
      const Eigen::Vector3d o_W = T_WC.translation();
      // Analytic ray-plane distances; the wall is bounded (6 m x 2 m around wall_p_W).
      double best_t = std::numeric_limits<double>::infinity();
      double best_cos = 1.0;  // |n . d| of the hit plane
      int best_id = 0;
      const double t_wall = s.wall_n_W.dot(s.wall_p_W - o_W) / s.wall_n_W.dot(d_W);
      const Eigen::Vector3d q = o_W + t_wall * d_W - s.wall_p_W;
      const Eigen::Matrix3d R_WO = s.scene.object(s.wall_id).T_WO.linear();
      const Eigen::Vector3d q_O = R_WO.transpose() * q;
      if (t_wall > 0 && std::abs(q_O.x()) <= 3.0 && std::abs(q_O.y()) <= 1.0) {
        best_t = t_wall;
        best_cos = std::abs(s.wall_n_W.dot(d_W));
        best_id = s.wall_id;
      }
      const double t_ground = s.ground_n_W.dot(s.ground_p_W - o_W) / s.ground_n_W.dot(d_W);
      if (t_ground > 0 && t_ground < best_t) {
        best_t = t_ground;
        best_cos = std::abs(s.ground_n_W.dot(d_W));
        best_id = s.ground_id;
      }
      const float depth = out.depth_C.at<float>(y, x);
      const int id = out.object_id.at<int32_t>(y, x);
      // Pixels whose ray grazes the wall edge within 1 mm may legitimately go either way.
      const bool near_edge = t_wall > 0 && (std::abs(std::abs(q_O.x()) - 3.0) < 1e-3 ||
                                            std::abs(std::abs(q_O.y()) - 1.0) < 1e-3);
      if (near_edge) continue;
      ASSERT_EQ(id, best_id) << "pixel " << x << "," << y;
      if (best_id == 0) {
        EXPECT_TRUE(std::isinf(depth));
        ++sky;
        continue;
      }
      (best_id == s.wall_id ? wall : ground)++;
      const double z = best_t * d_C.z();
      // Rays are cached as float (direction error ~1e-7 rad), which moves the hit by a relative
      // ~1e-7 / |n . d| (grazing rays amplify it); depth itself is float (6e-8 relative).
      const double tolerance = 1e-6 / best_cos;
      worst_relative = std::max(worst_relative, std::abs(depth - z) / std::abs(z) / tolerance);
    }
  }
  EXPECT_LT(worst_relative, 1.0);  // in units of each pixel's tolerance
  EXPECT_GT(wall, 1000);
  EXPECT_GT(ground, 1000);
  if (GetParam()) {
    EXPECT_GT(sky, 100);  // the fisheye sees above the wall
  }
}

// Finds the board's inner corners in the rendered image and compares each with the projection
// of its own 3-D corner through the camera model (findChessboardCorners lists them row by row
// from either end of the board; the end is taken from the first corner). Returns the largest
// error [px] (or +inf when the board is not found).
double ChessboardCornerError(const perception::CameraModel& camera, const Eigen::Isometry3d& T_WO,
                             const Eigen::Isometry3d& T_WC, double square_m) {
  constexpr int kSquaresX = 9, kSquaresY = 7;
  const double margin = square_m;
  Scene scene;
  SceneObject board;
  board.name = "board";
  board.primitive =
      Rectangle{{kSquaresX * square_m + 2 * margin, kSquaresY * square_m + 2 * margin}, {}, {}};
  board.material.texture = std::make_shared<const Texture>(
      Texture::Checkerboard(square_m, kSquaresX, kSquaresY, margin));
  board.material.color = Rgb::Ones();
  board.T_WO = T_WO;
  scene.AddObject(board);
  scene.sky.horizon_color = scene.sky.zenith_color = scene.sky.ground_color = Rgb::Constant(0.5f);
  scene.lighting.ambient = 1.0f;  // uniform light: full contrast whatever the board's tilt
  scene.lighting.directional = 0.0f;
  RayCaster caster;
  RenderOptions options;
  options.supersampling = 4;  // 16 rays per pixel: edge coverage quantized to 1/16
  const RenderOutput out = caster.Render(scene, camera, T_WC, options);
  CameraEffects effects({});
  const cv::Mat image = effects.ToImage8U(out.radiance, 0);

  std::vector<cv::Point2f> found;
  const cv::Size pattern(kSquaresX - 1, kSquaresY - 1);
  if (!cv::findChessboardCorners(image, pattern, found,
                                 cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
    return std::numeric_limits<double>::infinity();
  }
  cv::cornerSubPix(image, found, cv::Size(4, 4), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-4));
  const Eigen::Isometry3d T_CO = T_WC.inverse() * T_WO;
  std::vector<Eigen::Vector2d> projected;
  for (int j = 1; j < kSquaresY; ++j) {
    for (int i = 1; i < kSquaresX; ++i) {
      // Inner corner (i, j) at u, v = margin + (i, j) * square; p_O = uv - size / 2.
      const Eigen::Vector3d p_O((i - 0.5 * kSquaresX) * square_m, (j - 0.5 * kSquaresY) * square_m,
                                0.0);
      Eigen::Vector2d px;
      if (!camera.Project(T_CO * p_O, &px)) return std::numeric_limits<double>::infinity();
      projected.push_back(px);
    }
  }
  const auto distance = [](const cv::Point2f& f, const Eigen::Vector2d& px) {
    return std::hypot(f.x - px.x(), f.y - px.y());
  };
  if (distance(found.front(), projected.front()) > distance(found.front(), projected.back())) {
    std::reverse(found.begin(), found.end());
  }
  double worst = 0.0;
  for (std::size_t k = 0; k < projected.size(); ++k) {
    worst = std::max(worst, distance(found[k], projected[k]));
  }
  return worst;
}

TEST_P(RayCasterCameraTest, ChessboardCornersMatchProjectedGroundTruth) {
  // Board tilted 25 deg / 15 deg, in front of the camera (in the fisheye's central region).
  const bool fisheye = GetParam();
  const double distance = fisheye ? 0.3 : 0.8;
  const double square = fisheye ? 0.035 : 0.04;
  const Eigen::Isometry3d T_WC = Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d T_WO = Pose(Eigen::Vector3d(0.26, 0.44, 0.05), {0.03, -0.02, distance});
  const double error = ChessboardCornerError(*camera_, T_WO, T_WC, square);
  RecordProperty("max_corner_error_px", std::to_string(error));
  std::printf("max corner error (%s): %.4f px\n", camera_->model_name().c_str(), error);
  // Brief: every inner corner within 0.3 px of its projection.
  EXPECT_LT(error, 0.3);
}

TEST(RayCasterTest, ChessboardCornersFarOffAxisInTheFisheyeMatchProjectedGroundTruth) {
  // The board centre kOffAxisDeg from the optical axis towards +x_C, facing the camera, where
  // the 180 deg fisheye compresses the image most: its inner corners lie 48-92 deg off axis.
  constexpr double kOffAxisDeg = 70.0;
  const auto camera = testing::MakeTestFisheye();
  const double angle = kOffAxisDeg * M_PI / 180.0;
  const Eigen::Vector3d direction_C(std::sin(angle), 0.0, std::cos(angle));
  // z_O along the viewing ray (the board's front, +z_O seen, faces the camera), y_O = y_C.
  const Eigen::Isometry3d T_WO = Pose(Eigen::Vector3d(0.0, angle, 0.0), 0.3 * direction_C);
  const double error = ChessboardCornerError(*camera, T_WO, Eigen::Isometry3d::Identity(), 0.035);
  RecordProperty("max_corner_error_px", std::to_string(error));
  std::printf("max corner error (fisheye, %.0f deg off axis): %.4f px\n", kOffAxisDeg, error);
  EXPECT_LT(error, 0.3);
}

INSTANTIATE_TEST_SUITE_P(PinholeAndFisheye, RayCasterCameraTest, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "Fisheye" : "Pinhole"; });

// A textured scene with every primitive type, for determinism tests.
Scene TexturedGapScene() {
  Scene scene;
  ProceduralTextureParams params;
  params.size_px = 128;
  SceneObject ground{
      "ground", GroundPlane{}, {MakeGrassTexture(params)}, Pose({0, 0, 0}, {0, 0, -1.5})};
  scene.AddObject(ground);
  Rectangle wall{{3.0, 2.0}, {{{-0.5, -0.4}, {0.5, -0.4}, {0.5, 0.4}, {-0.5, 0.4}}}, {}};
  scene.AddObject(
      {"gap", wall, {MakeNewspaperTexture(params)}, Pose({0.0, M_PI / 2, 0.0}, {3.0, 0.0, 0.0})});
  scene.AddObject({"back",
                   Rectangle{{10.0, 6.0}, {}, {}},
                   {MakeValueNoiseTexture(params)},
                   Pose({0.0, M_PI / 2, 0.0}, {6.0, 0.0, 0.0})});
  scene.AddObject(
      {"tree", Cylinder{0.2, 4.0}, {MakeBarkTexture(params)}, Pose({0, 0, 0}, {4.0, 1.5, -1.5})});
  scene.AddObject({"ball", Sphere{0.3}, {}, Pose({0, 0, 0}, {2.0, -1.0, 0.5})});
  scene.AddObject({"crate", Box{{0.5, 0.5, 0.5}}, {}, Pose({0, 0, 0.3}, {2.5, 1.0, -1.0})});
  SceneObject led{"led", Led{}, {}, Pose({0, 0, 0}, {2.0, 0.3, 0.2})};
  scene.AddObject(led);
  return scene;
}

TEST(RayCasterTest, OutputIsIndependentOfThreadCountAndRepeatable) {
  const Scene scene = TexturedGapScene();
  // Half resolution keeps the three renders (and ray tables) fast.
  const auto camera = testing::MakeTestFisheye()->Scaled(376, 240);
  const Eigen::Isometry3d T_WC = LookAt({0, 0, 0}, {1.0, 0.05, -0.1});
  RenderOptions options;
  options.color = true;
  options.supersampling = 2;
  RenderOutput parallel, serial, again;
  RayCaster caster;
  caster.Render(scene, *camera, T_WC, options, &parallel);
  RayCaster().Render(scene, *camera, T_WC, options, &again);
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    RayCaster().Render(scene, *camera, T_WC, options, &serial);
  }
  for (const cv::Mat* m : {&serial.radiance, &again.radiance}) {
    EXPECT_EQ(cv::norm(parallel.radiance, *m, cv::NORM_INF), 0.0);
  }
  EXPECT_EQ(cv::norm(parallel.object_id, serial.object_id, cv::NORM_INF), 0.0);
  // The scene shows several objects (not a trivially uniform image).
  double min_id, max_id;
  cv::minMaxLoc(parallel.object_id, &min_id, &max_id);
  EXPECT_EQ(min_id, 0.0);
  EXPECT_GE(max_id, 6.0);
}

TEST(RayCasterTest, AdaptiveSupersamplingEqualsFullSupersamplingWhereItMatters) {
  // Every primitive with smooth textures, plus a checkerboard (hard-edged texture) in view.
  Scene scene = TexturedGapScene();
  const int board = scene.AddObject(
      {"board",
       Rectangle{{1.2, 0.9}, {}, {}},
       {std::make_shared<const Texture>(Texture::Checkerboard(0.1, 10, 7, 0.1)), Rgb::Ones()},
       Pose({0.3, M_PI / 2 + 0.4, 0.0}, {2.2, 0.6, 0.3})});
  const auto camera = testing::MakeTestFisheye()->Scaled(376, 240);
  const Eigen::Isometry3d T_WC = LookAt({0, 0, 0}, {1.0, 0.05, -0.1});
  RenderOptions options;
  options.supersampling = 2;
  RayCaster caster;
  const RenderOutput adaptive = caster.Render(scene, *camera, T_WC, options);
  options.adaptive_supersampling = false;
  const RenderOutput full = caster.Render(scene, *camera, T_WC, options);
  options.supersampling = 1;
  const RenderOutput single = caster.Render(scene, *camera, T_WC, options);
  const cv::Mat& ids = full.object_id;
  double worst_at_edges = 0.0, worst_on_board = 0.0, sum_elsewhere = 0.0, single_at_edges = 0.0;
  int edges = 0, board_pixels = 0, elsewhere = 0;
  for (int y = 1; y + 1 < ids.rows; ++y) {
    for (int x = 1; x + 1 < ids.cols; ++x) {
      const double error =
          std::abs(adaptive.radiance.at<float>(y, x) - full.radiance.at<float>(y, x));
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) edge |= ids.at<int>(y + dy, x + dx) != ids.at<int>(y, x);
      }
      if (edge) {
        worst_at_edges = std::max(worst_at_edges, error);
        single_at_edges +=
            std::abs(single.radiance.at<float>(y, x) - full.radiance.at<float>(y, x));
        ++edges;
      } else if (ids.at<int>(y, x) == board) {
        worst_on_board = std::max(worst_on_board, error);
        ++board_pixels;
      } else {
        sum_elsewhere += error;
        ++elsewhere;
      }
    }
  }
  std::printf(
      "adaptive vs full 2x2: worst at %d object edges %.2g, worst on board %.2g, mean "
      "elsewhere %.2g (k = 1 at edges: mean %.2g)\n",
      edges, worst_at_edges, worst_on_board, sum_elsewhere / elsewhere, single_at_edges / edges);
  ASSERT_GT(edges, 1000);
  ASSERT_GT(board_pixels, 1000);
  // Object edges and the checkerboard's texture edges get the same k x k rays as full
  // supersampling; inside uniform squares the centre sample equals the mean of the 4 equal
  // samples up to float rounding (1e-6 of a radiance ~1).
  EXPECT_LT(worst_at_edges, 1e-6);
  EXPECT_LT(worst_on_board, 1e-6);
  // Smooth textures: the centre sample at the pixel's mip level vs 4 samples one level finer
  // differ by texture detail below the pixel scale, well under one grey level (1/255) on average.
  EXPECT_LT(sum_elsewhere / elsewhere, 1.0 / 255.0);
  // Without supersampling the edges are visibly off (the test would notice a fallback to k = 1).
  EXPECT_GT(single_at_edges / edges, 0.01);
}

TEST(RayCasterTest, IdsAndDepthsMatchBruteForceIntersectionInClutter) {
  // The renderer tests each ray only against its image tile's candidates, nearest bound first,
  // and stops at the first candidate that cannot be nearer than the hit so far; Scene::Intersect
  // tests every object. Clutter: every primitive, rows of objects hiding each other at several
  // depths, a plane behind the camera and one seen edge-on.
  Scene scene = TexturedGapScene();
  for (int i = 0; i < 6; ++i) {
    const double x = 1.5 + 0.6 * i;
    scene.AddObject({"post" + std::to_string(i),
                     Cylinder{0.12, 2.5},
                     {},
                     Pose({0, 0, 0}, {x, -0.8 + 0.25 * i, -1.5})});
    scene.AddObject({"cube" + std::to_string(i),
                     Box{{0.3, 0.3, 0.3}},
                     {},
                     Pose({0.2 * i, 0, 0.1}, {x, 0.4 - 0.2 * i, 0.1 * i})});
    scene.AddObject(
        {"orb" + std::to_string(i), Sphere{0.15}, {}, Pose({0, 0, 0}, {x + 0.3, 0.1 * i, 0.6})});
  }
  scene.AddObject(
      {"behind", Rectangle{{4.0, 4.0}, {}, {}}, {}, Pose({0.0, M_PI / 2, 0.0}, {-2.0, 0.0, 0.0})});
  scene.AddObject(
      {"edge_on", Rectangle{{2.0, 2.0}, {}, {}}, {}, Pose({M_PI / 2, 0.0, 0.0}, {2.0, 0.0, 0.0})});
  const auto camera = testing::MakeTestFisheye()->Scaled(376, 240);
  const Eigen::Isometry3d T_WC = LookAt({0, 0, 0}, {1.0, 0.05, -0.1});
  const RenderOutput out = RayCaster().Render(scene, *camera, T_WC);
  int mismatches = 0, compared = 0;
  double worst_depth = 0.0;  // relative depth error in units of the tolerance
  for (int y = 0; y < camera->height(); ++y) {
    for (int x = 0; x < camera->width(); ++x) {
      // The renderer's cached ray (float), so both sides trace the same direction.
      const Eigen::Vector3d d_C =
          camera->Unproject({double(x), double(y)}).normalized().cast<float>().cast<double>();
      const std::optional<Hit> hit = scene.Intersect(T_WC.translation(), T_WC.linear() * d_C);
      const int id = out.object_id.at<int32_t>(y, x);
      if (!hit) {
        mismatches += id != 0;
      } else if (id != hit->object_id) {
        ++mismatches;
      } else {
        const Eigen::Vector3d u_C = d_C.normalized();
        const double z = hit->t_m * u_C.z();
        // As in DepthAndIdsEqualAnalyticRayPlaneIntersections: 1e-6 relative over the cosine of
        // incidence (grazing rays amplify rounding).
        const double cos_incidence = std::abs(hit->n_W.dot(T_WC.linear() * u_C));
        const double tolerance = 1e-6 / cos_incidence;
        worst_depth = std::max(worst_depth,
                               std::abs(out.depth_C.at<float>(y, x) - z) / std::abs(z) / tolerance);
      }
      ++compared;
    }
  }
  std::printf(
      "brute force vs renderer: %d of %d pixels differ, worst depth error %.2g "
      "tolerances\n",
      mismatches, compared, worst_depth);
  // Both sides evaluate the same ray, but in differently rounded object frames (T_OC vs T_OW):
  // a ray grazing a silhouette within ~1e-15 m may go either way; a culling error would lose
  // whole tiles (256 px).
  EXPECT_LE(mismatches, 3);
  EXPECT_LT(worst_depth, 1.0);  // in units of each pixel's tolerance
}

TEST(RayCasterTest, RayCacheFollowsTheCamera) {
  // Same model name and size, different focal length: the cached rays must not be reused.
  PlaneScene s;
  const perception::PinholeCamera narrow(320, 240, {300.0, 300.0, 159.5, 119.5});
  const perception::PinholeCamera wide(320, 240, {150.0, 150.0, 159.5, 119.5});
  const Eigen::Isometry3d T_WC = LookAt(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX());
  RayCaster caster;
  caster.Render(s.scene, narrow, T_WC);
  const RenderOutput out = caster.Render(s.scene, wide, T_WC);
  // Pixel (60, 100) of the wide camera looks 33.6 deg left (the narrow one's 18.3 deg).
  const Eigen::Vector3d d_C = wide.Unproject({60.0, 100.0}).normalized();
  const Eigen::Vector3d d_W = T_WC.linear() * d_C;
  const double z = s.wall_n_W.dot(s.wall_p_W) / s.wall_n_W.dot(d_W) * d_C.z();
  EXPECT_NEAR(out.depth_C.at<float>(100, 60), z, 1e-5 * z);  // float depth
}

TEST(RayCasterTest, RejectsBadOptions) {
  PlaneScene s;
  const auto camera = testing::MakeTestPinhole();
  RenderOptions options;
  options.supersampling = 0;
  RayCaster caster;
  EXPECT_THROW(caster.Render(s.scene, *camera, Eigen::Isometry3d::Identity(), options),
               std::invalid_argument);
}

}  // namespace
}  // namespace aperture::sim
