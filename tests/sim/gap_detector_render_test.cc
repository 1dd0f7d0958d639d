// GapDetector on rendered images with ground truth from the renderer (seed 000, Sec. III-A).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "perception/camera/optical_axes.h"
#include "perception/gap/gap_detector.h"
#include "render_test_util.h"
#include "sim/render/camera_effects.h"
#include "sim/render/ray_caster.h"
#include "sim/scene/gap_pattern_object.h"
#include "sim/scene/scene.h"
#include "tests/support/rotation_error.h"

namespace aperture::sim {
namespace {

using test_support::RotationErrorDeg;

using perception::CameraModel;
using perception::GapDetection;
using perception::GapDetector;
using perception::GapDetectorParams;

const Eigen::Vector2d kPanelSize(1.8, 1.2);  // 0.25 m white margin around the outer band

SceneObject MakeGapPanel(const GapDetectorParams& p, const Eigen::Isometry3d& T_WG) {
  return MakeGapPatternObject(p, kPanelSize, T_WG);
}

// Procedural textures are costly to generate: build them once for all tests of this file.
struct ClutterTextures {
  std::shared_ptr<const Texture> grass, noise, bark, newspaper;
};
const ClutterTextures& Textures() {
  static const ClutterTextures textures = [] {
    ProceduralTextureParams tex;
    tex.seed = 7;
    ClutterTextures t;
    t.grass = MakeGrassTexture(tex);
    t.noise = MakeValueNoiseTexture(tex);
    tex.seed = 8;
    t.bark = MakeBarkTexture(tex);
    t.newspaper = MakeNewspaperTexture(tex);
    return t;
  }();
  return textures;
}

// Ground with grass, a noise-textured wall seen through the opening, trees and boxes.
void AddClutter(Scene* scene, double wall_x_m) {
  const ClutterTextures& tex = Textures();
  scene->AddObject(
      {"ground", GroundPlane{}, {tex.grass, Rgb::Ones(), 1.0}, Eigen::Isometry3d::Identity()});
  Eigen::Isometry3d T_wall = Eigen::Isometry3d::Identity();
  T_wall.linear() = perception::OpticalAxesAlongX();  // faces -x_W
  T_wall.translation() = Eigen::Vector3d(wall_x_m, 0.0, 3.0);
  scene->AddObject({"wall", Rectangle{{30.0, 6.0}, {}, {}}, {tex.noise, Rgb::Ones(), 1.0}, T_wall});
  for (int i = 0; i < 6; ++i) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(wall_x_m - 1.5 - 0.7 * i, -7.0 + 2.8 * i, 0.0);
    scene->AddObject(
        {"tree" + std::to_string(i), Cylinder{0.2, 4.0}, {tex.bark, Rgb::Ones(), 1.0}, T});
    T.translation() += Eigen::Vector3d(-1.0, 1.2, 0.4);
    T.linear() = Eigen::AngleAxisd(0.4 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    scene->AddObject({"box" + std::to_string(i),
                      Box{Eigen::Vector3d(0.8, 0.6, 0.8)},
                      {tex.newspaper, Rgb::Ones(), 1.0},
                      T});
  }
}

// Gap at p_W with the given roll (about z_G) and pitch (about x_G); with zero angles it stands
// vertically, facing -x_W (z_G = +x_W), x_G = -y_W, y_G = -z_W.
Eigen::Isometry3d GapPose(double roll, double pitch, const Eigen::Vector3d& p_W) {
  const Eigen::Matrix3d R0 = perception::OpticalAxesAlongX();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R0 * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()) *
               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX());
  T.translation() = p_W;
  return T;
}

// The detector's symmetry convention (gap_detector.h) applied to a ground-truth pose.
Eigen::Isometry3d Canonical(Eigen::Isometry3d T_CG) {
  if (T_CG.linear()(0, 0) < 0.0)
    T_CG.linear() = T_CG.linear() * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ());
  return T_CG;
}

struct Sample {
  double distance_m;
  double position_error_m;
  double rotation_error_deg;
};

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() / 2];
}

enum class Lens { kPinhole, kFisheye };

class GapDetectorRenderTest : public ::testing::TestWithParam<Lens> {
 protected:
  std::shared_ptr<const CameraModel> MakeCamera() const {
    return GetParam() == Lens::kPinhole
               ? std::shared_ptr<const CameraModel>(testing::MakeTestPinhole())
               : std::shared_ptr<const CameraModel>(testing::MakeTestFisheye());
  }
};

// Random gap inclinations (roll 0-45 deg, pitch 0-30 deg, the seed's range), viewing angles and
// distances 1-5 m; the gap anywhere in the image.
TEST_P(GapDetectorRenderTest, PoseAccuracyAndDetectionRate) {
  const auto camera = MakeCamera();
  GapDetectorParams params;
  params.use_roi = false;
  GapDetector detector(params, camera);
  const int gap_id_expected = 1;
  std::mt19937 rng(GetParam() == Lens::kPinhole ? 11 : 12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  CameraEffectsParams effects;
  effects.read_noise_sigma = 0.004;  // ~1 gray level
  effects.seed = 3;
  RayCaster caster;
  RenderOptions options;
  options.supersampling = 2;

  std::vector<Sample> samples;
  int in_view = 0, detected = 0;
  constexpr int kFrames = 24;
  for (int frame = 0; frame < kFrames; ++frame) {
    const double roll = unit(rng) * 45.0 * M_PI / 180.0;
    const double pitch = unit(rng) * 30.0 * M_PI / 180.0;
    const Eigen::Isometry3d T_WG = GapPose(roll, pitch, Eigen::Vector3d(0.0, 0.0, 2.0));
    Scene scene;
    const int gap_id = scene.AddObject(MakeGapPanel(params, T_WG));
    ASSERT_EQ(gap_id, gap_id_expected);
    AddClutter(&scene, 7.0);
    const double distance = 1.0 + 4.0 * (frame + unit(rng)) / kFrames;  // stratified 1-5 m
    const double azimuth = (unit(rng) - 0.5) * 60.0 * M_PI / 180.0;
    const double elevation = (unit(rng) - 0.5) * 30.0 * M_PI / 180.0;
    const Eigen::Vector3d dir_G(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                                std::cos(azimuth) * std::cos(elevation));
    const Eigen::Vector3d p_WC = T_WG * (-distance * dir_G);
    // Look at a point beside the gap so it appears off-centre (more so on the fisheye).
    const double spread = GetParam() == Lens::kPinhole ? 0.25 : 0.8;
    const Eigen::Vector3d target_W =
        T_WG.translation() +
        spread * distance *
            Eigen::Vector3d((unit(rng) - 0.5), (unit(rng) - 0.5), 0.6 * (unit(rng) - 0.5));
    Eigen::Isometry3d T_WC = testing::LookAt(p_WC, target_W - p_WC);
    T_WC.linear() = T_WC.linear() * Eigen::AngleAxisd((unit(rng) - 0.5) * 30.0 * M_PI / 180.0,
                                                      Eigen::Vector3d::UnitZ());

    const RenderOutput out = caster.Render(scene, *camera, T_WC, options);
    const cv::Mat image = CameraEffects(effects).ToImage8U(out.radiance, frame);
    const Eigen::Isometry3d T_CG_true = Canonical(T_WC.inverse() * T_WG);
    if (!GapPatternInView(*camera, params, T_CG_true, out.object_id, gap_id)) continue;
    ++in_view;
    const GapDetection d = detector.Detect(image);
    if (!d.detected()) {
      ADD_FAILURE() << "frame " << frame << " missed at " << distance
                    << " m: " << GapDetectionStatusName(d.status);
      continue;
    }
    ++detected;
    samples.push_back({distance, (d.T_CG.translation() - T_CG_true.translation()).norm(),
                       RotationErrorDeg(d.T_CG, T_CG_true)});
    // The covariance is a proper covariance of a well-constrained pose.
    EXPECT_TRUE(d.covariance.isApprox(d.covariance.transpose(), 1e-9));
    using Mat6 = Eigen::Matrix<double, 6, 6>;
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat6>(d.covariance).eigenvalues().minCoeff(), 0.0);
  }
  // Enough frames with the whole pattern in view for the statistics to mean something.
  ASSERT_GE(in_view, kFrames * 2 / 3);
  // >= 99 % detection rate: with fewer than 100 frames that means every frame.
  EXPECT_EQ(detected, in_view);

  std::vector<double> relative_position, rotation;
  for (const char* band : {"1-2 m", "2-3.5 m", "3.5-5 m"}) {
    const double lo = band[0] == '1' ? 1.0 : band[0] == '2' ? 2.0 : 3.5;
    const double hi = band[0] == '1' ? 2.0 : band[0] == '2' ? 3.5 : 5.0;
    std::vector<double> pos, rot;
    for (const Sample& s : samples) {
      if (s.distance_m < lo || s.distance_m >= hi) continue;
      pos.push_back(100.0 * s.position_error_m / s.distance_m);
      rot.push_back(s.rotation_error_deg);
    }
    if (pos.empty()) continue;
    std::printf(
        "[%s] %-8s n=%2zu position error %% of distance: median %.3f max %.3f | rotation deg: "
        "median %.3f max %.3f\n",
        GetParam() == Lens::kPinhole ? "pinhole" : "fisheye", band, pos.size(), Median(pos),
        *std::max_element(pos.begin(), pos.end()), Median(rot),
        *std::max_element(rot.begin(), rot.end()));
  }
  for (const Sample& s : samples) {
    relative_position.push_back(s.position_error_m / s.distance_m);
    rotation.push_back(s.rotation_error_deg);
  }
  std::printf("detected %d of %d frames with the pattern in view\n", detected, in_view);
  // The targets: median position error <= 1 % of the distance, rotation <= 1 deg.
  EXPECT_LE(Median(relative_position), 0.01);
  EXPECT_LE(Median(rotation), 1.0);
}

// A short approach: ROI tracking must give the same poses as a full-image search.
TEST_P(GapDetectorRenderTest, RoiTrackingMatchesFullSearch) {
  const auto camera = MakeCamera();
  GapDetectorParams params;
  GapDetector tracker(params, camera);
  GapDetector full(params, camera);
  const Eigen::Isometry3d T_WG = GapPose(0.5, 0.3, Eigen::Vector3d(0.0, 0.0, 2.0));
  Scene scene;
  scene.AddObject(MakeGapPanel(params, T_WG));
  AddClutter(&scene, 7.0);
  RayCaster caster;
  RenderOptions options;
  options.supersampling = 2;
  int from_roi = 0;
  for (int frame = 0; frame < 6; ++frame) {
    const Eigen::Vector3d p_WC =
        T_WG * Eigen::Vector3d(0.3 - 0.05 * frame, 0.1, -3.5 + 0.3 * frame);
    const Eigen::Isometry3d T_WC = testing::LookAt(p_WC, T_WG.translation() - p_WC);
    const cv::Mat image =
        CameraEffects({}).ToImage8U(caster.Render(scene, *camera, T_WC, options).radiance, frame);
    const GapDetection tracked = tracker.Detect(image);
    const GapDetection searched = full.DetectFullImage(image);
    ASSERT_TRUE(tracked.detected()) << "frame " << frame;
    ASSERT_TRUE(searched.detected()) << "frame " << frame;
    from_roi += tracked.from_roi ? 1 : 0;
    // Both refine on the same edge samples up to the rough corners that seed the sampling:
    // agreement within 1 mm and 0.05 deg is far below the 1 % / 1 deg accuracy.
    EXPECT_LT((tracked.T_CG.translation() - searched.T_CG.translation()).norm(), 1e-3)
        << "frame " << frame;
    EXPECT_LT(RotationErrorDeg(tracked.T_CG, searched.T_CG), 0.05) << "frame " << frame;
  }
  EXPECT_EQ(from_roi, 5);  // every frame after the first is found in the ROI
}

INSTANTIATE_TEST_SUITE_P(Lenses, GapDetectorRenderTest,
                         ::testing::Values(Lens::kPinhole, Lens::kFisheye),
                         [](const ::testing::TestParamInfo<Lens>& info) {
                           return info.param == Lens::kPinhole ? "Pinhole" : "Fisheye";
                         });

// Close up on the fisheye the pattern's sides are strongly curved in the image (the pattern
// spans +-41 deg at 0.75 m): polarity checks and edge sampling must follow the curved sides.
TEST(GapDetectorCloseUpTest, FisheyeCloseUpWithCurvedSides) {
  const auto camera = std::shared_ptr<const CameraModel>(testing::MakeTestFisheye());
  GapDetector detector(GapDetectorParams{}, camera);
  const Eigen::Isometry3d T_WG = GapPose(0.0, 0.0, Eigen::Vector3d(0.0, 0.0, 2.0));
  Scene scene;
  scene.AddObject(MakeGapPanel(GapDetectorParams{}, T_WG));
  AddClutter(&scene, 7.0);
  RayCaster caster;
  RenderOptions options;
  options.supersampling = 2;
  for (const Eigen::Vector3d& p_GC :
       {Eigen::Vector3d(0.0, 0.0, -0.75), Eigen::Vector3d(0.0, 0.0, -0.9),
        Eigen::Vector3d(0.2, -0.1, -0.8)}) {
    const Eigen::Vector3d p_WC = T_WG * p_GC;
    const Eigen::Isometry3d T_WC = testing::LookAt(p_WC, T_WG.translation() - p_WC);
    const cv::Mat image =
        CameraEffects({}).ToImage8U(caster.Render(scene, *camera, T_WC, options).radiance, 0);
    const GapDetection d = detector.DetectFullImage(image);
    ASSERT_TRUE(d.detected()) << p_GC.transpose() << ": " << GapDetectionStatusName(d.status);
    const Eigen::Isometry3d T_CG_true = Canonical(T_WC.inverse() * T_WG);
    // The accuracy targets (1 % of the distance, 1 deg) on a single frame.
    EXPECT_LT((d.T_CG.translation() - T_CG_true.translation()).norm(), 0.01 * p_GC.norm());
    EXPECT_LT(RotationErrorDeg(d.T_CG, T_CG_true), 1.0);
  }
}

// Far and steep on the fisheye (issue 22): at ~5 m the 5 cm white band is ~2 px wide, its two
// edges merge in the dilated edge map and the inner quadrangle's contour loses a corner, so the
// tight polygon tolerance gives it five vertices. Views from the bench's misses (gap roll
// 35-55 deg, pitch 10-28 deg, 25-35 deg off the normal, the camera rolled): every one detected
// within the accuracy targets, and with the tolerance never widened some are missed (the views
// exercise the retry). The short inner sides (~15 px) also need the denser edge sampling of
// short sides. Accuracy: the medians within the 1 % / 1 deg of the render tests (0.24 % and
// 0.49 deg measured; 0.66 % and 0.99 deg before edge samples off the refined edges were dropped;
// single views reach 1.6 deg, the bench's 4-6 m band has p90 ~0.5 deg).
TEST(GapDetectorFarSteepTest, InnerQuadrangleWithACutCornerIsFound) {
  const auto camera = std::shared_ptr<const CameraModel>(testing::MakeTestFisheye());
  GapDetectorParams params;
  params.use_roi = false;
  GapDetectorParams tight = params;
  tight.approx_epsilon_max_ratio = tight.approx_epsilon_ratio;
  GapDetector detector(params, camera);
  GapDetector tight_detector(tight, camera);
  RayCaster caster;
  RenderOptions options;
  options.supersampling = 2;
  CameraEffectsParams effects;
  effects.read_noise_sigma = 0.004;
  int views = 0, detected = 0, detected_tight = 0;
  std::vector<double> relative_position, rotation;
  for (int i = 0; i < 12; ++i) {
    const double roll = (35.0 + 20.0 * ((i * 5) % 12) / 11.0) * M_PI / 180.0;
    const double pitch = (10.0 + 18.0 * ((i * 7) % 12) / 11.0) * M_PI / 180.0;
    // At 4 m height the views from below stay above the ground.
    const Eigen::Isometry3d T_WG = GapPose(roll, pitch, Eigen::Vector3d(0.0, 0.0, 4.0));
    Scene scene;
    const int gap_id = scene.AddObject(MakeGapPanel(params, T_WG));
    AddClutter(&scene, 7.0);
    const double distance = 4.6 + 0.1 * i;
    const double off_normal = (25.0 + 10.0 * ((i * 3) % 4) / 3.0) * M_PI / 180.0;
    const double azimuth = 2.0 * M_PI * i / 12.0;
    const Eigen::Vector3d dir_G(std::sin(off_normal) * std::cos(azimuth),
                                std::sin(off_normal) * std::sin(azimuth), std::cos(off_normal));
    const Eigen::Vector3d p_WC = T_WG * (-distance * dir_G);
    Eigen::Isometry3d T_WC = testing::LookAt(p_WC, T_WG.translation() - p_WC);
    T_WC.linear() = T_WC.linear() *
                    Eigen::AngleAxisd((i % 5 - 2) * 12.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ());
    const RenderOutput out = caster.Render(scene, *camera, T_WC, options);
    const cv::Mat image = CameraEffects(effects).ToImage8U(out.radiance, i);
    const Eigen::Isometry3d T_CG_true = Canonical(T_WC.inverse() * T_WG);
    if (!GapPatternInView(*camera, params, T_CG_true, out.object_id, gap_id)) continue;  // clutter
    ++views;
    detected_tight += tight_detector.DetectFullImage(image).detected() ? 1 : 0;
    const GapDetection d = detector.DetectFullImage(image);
    if (!d.detected()) {
      ADD_FAILURE() << "view " << i << " at " << distance
                    << " m: " << GapDetectionStatusName(d.status);
      continue;
    }
    ++detected;
    relative_position.push_back((d.T_CG.translation() - T_CG_true.translation()).norm() / distance);
    rotation.push_back(RotationErrorDeg(d.T_CG, T_CG_true));
  }
  std::printf(
      "far steep views: %d of %d detected, %d without widening the tolerance; median position "
      "error %.3f %% of the distance, rotation %.3f deg\n",
      detected, views, detected_tight, 100.0 * Median(relative_position), Median(rotation));
  EXPECT_LE(Median(relative_position), 0.01);
  EXPECT_LE(Median(rotation), 1.0);
  ASSERT_GE(views, 10);
  EXPECT_EQ(detected, views);
  EXPECT_LT(detected_tight, views);
}

// Seen far off its normal across the long side, the pattern's long side looks shorter than its
// short side (1.3 m x cos 60-68 deg < 0.78 m): the first labelling (long image side = x_G) fails,
// the other must be found — the gap mission lost the gap this way in its approach at 42-44 deg
// roll with 18-29 deg pitch.
TEST(GapDetectorFarSteepTest, LongSideForeshortenedBelowTheShortSide) {
  const auto camera = std::shared_ptr<const CameraModel>(testing::MakeTestFisheye());
  GapDetectorParams params;
  params.use_roi = false;
  GapDetector detector(params, camera);
  RayCaster caster;
  RenderOptions options;
  options.supersampling = 2;
  const Eigen::Isometry3d T_WG = GapPose(0.75, 0.3, Eigen::Vector3d(0.0, 0.0, 3.0));
  Scene scene;
  const int gap_id = scene.AddObject(MakeGapPanel(params, T_WG));
  AddClutter(&scene, 7.0);
  int views = 0;
  for (const double off_normal_deg : {60.0, 64.0, 68.0}) {
    for (const double distance : {1.6, 2.5}) {
      const double a = off_normal_deg * M_PI / 180.0;
      // Off the normal in the x_G - z_G plane: x_G, the long side, is foreshortened.
      const Eigen::Vector3d p_WC =
          T_WG * Eigen::Vector3d(distance * std::sin(a), 0.05, -distance * std::cos(a));
      const Eigen::Isometry3d T_WC = testing::LookAt(p_WC, T_WG.translation() - p_WC);
      const RenderOutput out = caster.Render(scene, *camera, T_WC, options);
      const cv::Mat image = CameraEffects({}).ToImage8U(out.radiance, views);
      const Eigen::Isometry3d T_CG_true = Canonical(T_WC.inverse() * T_WG);
      ASSERT_TRUE(GapPatternInView(*camera, params, T_CG_true, out.object_id, gap_id));
      // The premise: the long side spans fewer pixels than the short one.
      const std::vector<Eigen::Vector3d> corners = detector.ModelCorners();
      Eigen::Vector2d c0, c1, c2;
      ASSERT_TRUE(camera->Project(T_CG_true * corners[0], &c0));
      ASSERT_TRUE(camera->Project(T_CG_true * corners[1], &c1));
      ASSERT_TRUE(camera->Project(T_CG_true * corners[2], &c2));
      ASSERT_LT((c1 - c0).norm(), (c2 - c1).norm()) << off_normal_deg << " deg";
      ++views;
      const GapDetection d = detector.DetectFullImage(image);
      ASSERT_TRUE(d.detected()) << off_normal_deg << " deg, " << distance
                                << " m: " << GapDetectionStatusName(d.status);
      EXPECT_LT((d.T_CG.translation() - T_CG_true.translation()).norm(), 0.01 * distance);
      EXPECT_LT(RotationErrorDeg(d.T_CG, T_CG_true), 1.0) << off_normal_deg << " deg";
    }
  }
  EXPECT_EQ(views, 6);
}

// No detection without a gap: a cluttered textured scene, all black, all white, pure noise.
TEST(GapDetectorNegativeTest, NoDetectionWithoutGap) {
  for (const auto& camera : {std::shared_ptr<const CameraModel>(testing::MakeTestPinhole()),
                             std::shared_ptr<const CameraModel>(testing::MakeTestFisheye())}) {
    GapDetector detector(GapDetectorParams{}, camera);
    Scene scene;
    AddClutter(&scene, 7.0);
    RayCaster caster;
    RenderOptions options;
    options.supersampling = 2;
    for (int view = 0; view < 3; ++view) {
      const Eigen::Vector3d p_WC(0.0, -1.5 + 1.5 * view, 1.5);
      const Eigen::Isometry3d T_WC =
          testing::LookAt(p_WC, Eigen::Vector3d(1.0, 0.3 * (1 - view), -0.15));
      const cv::Mat image =
          CameraEffects({}).ToImage8U(caster.Render(scene, *camera, T_WC, options).radiance, view);
      EXPECT_FALSE(detector.DetectFullImage(image).detected())
          << camera->model_name() << " view " << view;
    }
    const cv::Mat black(camera->height(), camera->width(), CV_8UC1, cv::Scalar(0));
    const cv::Mat white(camera->height(), camera->width(), CV_8UC1, cv::Scalar(255));
    cv::Mat noise(camera->height(), camera->width(), CV_8UC1);
    cv::RNG rng(5);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
    EXPECT_FALSE(detector.DetectFullImage(black).detected());
    EXPECT_FALSE(detector.DetectFullImage(white).detected());
    EXPECT_FALSE(detector.DetectFullImage(noise).detected());
  }
}

}  // namespace
}  // namespace aperture::sim
