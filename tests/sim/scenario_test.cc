// Scenarios: every built-in loads and renders a non-degenerate view, the gap pattern appears where
// its known geometry projects, every gapflyt opening kind is cut with its analytic area, the tags
// area holds every tagged object kind without overlaps, strict loading names file:line and key,
// seeds and randomization are reproducible, kinematic trajectories and body-attached objects
// follow their definitions, and the 16-bit ground-truth encodings round as documented.
#include "sim/scenario/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>
#include <set>
#include <variant>

#include "perception/gap/gap_detector.h"
#include "sim/render/ray_caster.h"
#include "sim/scenario/ground_truth_images.h"
#include "sim/scenario/kinematic_trajectory.h"
#include "sim/scene/apriltag_object.h"

namespace aperture::sim {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// A file in the temp folder, removed at the end of the test.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& text)
      : path_((std::filesystem::temp_directory_path() /
               (name + "_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                "_" + std::to_string(reinterpret_cast<std::uintptr_t>(this)) + ".yaml"))
                  .string()) {
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::filesystem::remove(path_); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

ScenarioParams LoadScenario(const std::string& name, const std::vector<std::string>& sets = {},
                            const std::vector<std::string>& files = {}) {
  return LoadScenarioParams(ScenarioConfig(name, files, sets));
}

// One frame's radiance and ground truth from the render camera at T_WB (no sensor noise), with
// supersampling 1 to keep the tests fast.
RenderOutput RenderAt(Scenario& scenario, const Eigen::Isometry3d& T_WB) {
  scenario.SetVehiclePose(T_WB);
  const ScenarioCamera& camera = scenario.render_camera();
  RenderOptions options = camera.render;
  options.supersampling = 1;
  if (camera.effects.params().infrared) {
    options.reflectance_scale = camera.effects.params().infrared_reflectance_scale;
  }
  RayCaster caster;
  return caster.Render(scenario.scene(), *camera.model, camera.T_WC(T_WB), options);
}

// Object id at the pixel nearest to the projection of p_C (a test failure when p_C does not
// project).
int IdAt(const RenderOutput& out, const ScenarioCamera& camera, const Eigen::Vector3d& p_C) {
  Eigen::Vector2d px;
  EXPECT_TRUE(camera.model->Project(p_C, &px)) << p_C.transpose();
  return out.object_id.at<int>(
      cv::Point(static_cast<int>(std::lround(px.x())), static_cast<int>(std::lround(px.y()))));
}

std::set<std::string> VisibleNames(const Scenario& scenario, const cv::Mat& object_id) {
  std::set<std::string> names;
  for (int y = 0; y < object_id.rows; ++y) {
    for (int x = 0; x < object_id.cols; ++x) {
      const int id = object_id.at<int>(y, x);
      if (id > 0) names.insert(scenario.scene().object(id).name);
    }
  }
  return names;
}

bool AnyStartsWith(const std::set<std::string>& names, const std::string& prefix) {
  for (const std::string& name : names) {
    if (name.rfind(prefix, 0) == 0) return true;
  }
  return false;
}

class BuiltinScenarioTest : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinScenarioTest, LoadsAndRendersItsKeyObjects) {
  Scenario scenario = BuildScenario(LoadScenario(GetParam()));
  EXPECT_EQ(scenario.kind(), GetParam());
  const RenderOutput out = RenderAt(scenario, scenario.T_WB_start());
  cv::Scalar mean, stddev;
  cv::meanStdDev(out.radiance, mean, stddev);
  const std::set<std::string> visible = VisibleNames(scenario, out.object_id);
  // The object each scenario exists for is in view from the start pose.
  const std::map<std::string, std::string> key_prefix{
      {"gap", "gap"}, {"gapflyt", "gap"}, {"led", "led"}, {"tags", "tag"}, {"forest", "tree"}};
  EXPECT_TRUE(AnyStartsWith(visible, key_prefix.at(GetParam())))
      << GetParam() << ": key object not visible";
  if (GetParam() == "led") {
    // Infrared: a dark scene whose brightest pixels are the LEDs (>> the 3 % reflectance floor).
    double max_value = 0.0;
    cv::minMaxLoc(out.radiance, nullptr, &max_value);
    EXPECT_GT(max_value, 0.5);
    EXPECT_LT(mean[0], 0.05);
    EXPECT_TRUE(visible.count("led0") && visible.count("led1") && visible.count("led2") &&
                visible.count("led3"));
  } else {
    // Textured worlds: several objects and real contrast (a blank or single-colour frame has
    // stddev ~0; textures alone give > 0.05 of full scale).
    EXPECT_GE(visible.size(), 2u);
    EXPECT_GT(stddev[0], 0.05);
  }
}

INSTANTIATE_TEST_SUITE_P(AllBuiltins, BuiltinScenarioTest,
                         ::testing::Values("gap", "gapflyt", "led", "tags", "forest"));

// The black band of the gap pattern is dark and the panel and the white margin bright exactly
// where the known pattern geometry (gap.* parameters, T_WG from the scene) projects, for a level
// and a rolled gap.
class GapPatternTest : public ::testing::TestWithParam<double> {};

TEST_P(GapPatternTest, PatternAppearsWhereItProjects) {
  Scenario scenario =
      BuildScenario(LoadScenario("gap", {"gap.roll_deg=" + std::to_string(GetParam())}));
  const GapParams& gap = scenario.params().gap;
  Eigen::Isometry3d T_WB = scenario.T_WB_start();
  T_WB.translation().x() = gap.center_W.x() - 2.0;  // 2 m in front of the gap
  const RenderOutput out = RenderAt(scenario, T_WB);
  const ScenarioCamera& camera = scenario.render_camera();
  const Eigen::Isometry3d T_CG = camera.T_WC(T_WB).inverse() * scenario.scene().object("gap").T_WO;
  const int gap_id = scenario.scene().FindId("gap");
  // Probe points mid-way between the rectangle edges, along each corner's diagonal.
  const Eigen::Vector2d band = 0.25 * (gap.pattern_outer_m + gap.pattern_inner_m);
  const Eigen::Vector2d panel = 0.25 * (gap.panel_m + gap.pattern_outer_m);
  const Eigen::Vector2d margin = 0.25 * (gap.pattern_inner_m + gap.opening_m);
  for (const Eigen::Vector2d& sign : {Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1),
                                      Eigen::Vector2d(1, -1), Eigen::Vector2d(-1, -1)}) {
    const auto sample = [&](const Eigen::Vector2d& xy_G, int* id) {
      Eigen::Vector2d px;
      EXPECT_TRUE(camera.model->Project(T_CG * Eigen::Vector3d(xy_G.x(), xy_G.y(), 0.0), &px));
      EXPECT_TRUE(camera.model->IsInImage(px, 2.0));
      const cv::Point p(static_cast<int>(std::lround(px.x())),
                        static_cast<int>(std::lround(px.y())));
      *id = out.object_id.at<int>(p);
      return out.radiance.at<float>(p);
    };
    int band_id = 0, panel_id = 0, margin_id = 0;
    const float black = sample(band.cwiseProduct(sign), &band_id);
    const float white_panel = sample(panel.cwiseProduct(sign), &panel_id);
    const float white_margin = sample(margin.cwiseProduct(sign), &margin_id);
    // Albedo 0.05 vs 0.95 under >= the 0.45 ambient: black < 0.1, white > 0.4.
    EXPECT_LT(black, 0.1f);
    EXPECT_GT(white_panel, 0.4f);
    EXPECT_GT(white_margin, 0.4f);
    EXPECT_EQ(band_id, gap_id);
    EXPECT_EQ(panel_id, gap_id);
    EXPECT_EQ(margin_id, gap_id);
  }
  // Through the opening's centre: the room behind, not the panel.
  Eigen::Vector2d centre_px;
  ASSERT_TRUE(camera.model->Project(T_CG * Eigen::Vector3d::Zero(), &centre_px));
  EXPECT_NE(
      out.object_id.at<int>(cv::Point(std::lround(centre_px.x()), std::lround(centre_px.y()))),
      gap_id);
}

INSTANTIATE_TEST_SUITE_P(Rolls, GapPatternTest, ::testing::Values(0.0, 30.0));

// gap.pitch_deg rotates the panel about y_W (scenario_params.h): R_WG = Ry(pitch) * R_WG(0),
// centre unchanged, so the part above the opening leans away from the approach (+x_W).
TEST(GapScenarioTest, PitchRotatesThePanelAboutYWorld) {
  const Scenario level = BuildScenario(LoadScenario("gap"));
  const Scenario pitched = BuildScenario(LoadScenario("gap", {"gap.pitch_deg=25"}));
  const Eigen::Isometry3d& T_WG0 = level.scene().object("gap").T_WO;
  const Eigen::Isometry3d& T_WG = pitched.scene().object("gap").T_WO;
  const double pitch = 25.0 * M_PI / 180.0;
  EXPECT_TRUE(T_WG.linear().isApprox(
      Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix() * T_WG0.linear(),
      1e-12));
  EXPECT_TRUE(T_WG.translation().isApprox(T_WG0.translation(), 1e-12));
  const Eigen::Vector3d above_W = T_WG * Eigen::Vector3d(0.0, -0.5, 0.0);  // y_G points down
  EXPECT_NEAR(above_W.x() - T_WG.translation().x(), 0.5 * std::sin(pitch), 1e-12);
  EXPECT_NEAR(above_W.z() - T_WG.translation().z(), 0.5 * std::cos(pitch), 1e-12);
}

// Seed 002 Sec. IV: five opening kinds (GapFlytParams). From the start pose the opening's centre
// shows the background wall, the foreground wall surrounds it, and the hole's area in the id mask
// (background pixels * (Z / f)^2 on the fronto-parallel wall) matches the kind's analytic area.
class GapFlytShapeTest : public ::testing::TestWithParam<std::string> {};

TEST_P(GapFlytShapeTest, OpeningIsCutWithItsAnalyticArea) {
  ScenarioParams params = LoadScenario("gapflyt", {"gapflyt.shape=" + GetParam()});
  params.cameras.front().second.width = 320;
  params.cameras.front().second.height = 240;
  Scenario scenario = BuildScenario(params);
  const GapFlytParams& g = scenario.params().gapflyt;
  const RenderOutput out = RenderAt(scenario, scenario.T_WB_start());
  const ScenarioCamera& camera = scenario.render_camera();
  const SceneObject& wall = scenario.scene().object("gap");
  const Eigen::Isometry3d T_CG = camera.T_WC(scenario.T_WB_start()).inverse() * wall.T_WO;
  const int wall_id = scenario.scene().FindId("gap");
  const int background_id = scenario.scene().FindId("background");
  const auto id_at = [&](const Eigen::Vector2d& xy_G) {
    return IdAt(out, camera, T_CG * Eigen::Vector3d(xy_G.x(), xy_G.y(), 0.0));
  };
  EXPECT_EQ(id_at(Eigen::Vector2d::Zero()), background_id);
  const Eigen::Vector2d outside = g.size_m / 2.0 + Eigen::Vector2d::Constant(0.15);
  for (const Eigen::Vector2d& xy :
       {Eigen::Vector2d(outside.x(), 0.0), Eigen::Vector2d(-outside.x(), 0.0),
        Eigen::Vector2d(0.0, outside.y()), Eigen::Vector2d(0.0, -outside.y())}) {
    EXPECT_EQ(id_at(xy), wall_id) << xy.transpose();
  }
  const double w = g.size_m.x(), h = g.size_m.y();
  double expected_m2 = 0.0;
  if (GetParam() == "ellipse") expected_m2 = M_PI * w * h / 4.0;
  if (GetParam() == "triangle") expected_m2 = w * h / 2.0;
  if (GetParam() == "notched") expected_m2 = w * h * (1.0 - g.notch_depth_ratio / 4.0);
  if (GetParam() == "star") {  // 2n triangles between outer radius 1 and inner ratio, scaled
    const int n = g.star_points;
    expected_m2 = n * g.star_inner_ratio * std::sin(M_PI / n) * w * h / 4.0;
  }
  if (GetParam() == "polygon") {  // seeded: shoelace of the wall's hole
    const std::vector<Eigen::Vector2d>& v = std::get<Rectangle>(wall.primitive).polygon_holes.at(0);
    ASSERT_EQ(v.size(), 4u);
    for (size_t i = 0; i < v.size(); ++i) {
      const Eigen::Vector2d& a = v[i];
      const Eigen::Vector2d& b = v[(i + 1) % v.size()];
      expected_m2 += 0.5 * (a.x() * b.y() - a.y() * b.x());
    }
    expected_m2 = std::abs(expected_m2);
    EXPECT_GT(expected_m2, 0.5 * w * h);  // corners at 75..100 % of the box
  }
  const Eigen::Vector4d intrinsics = camera.model->intrinsics();  // fx, fy, cx, cy
  const double z_m = T_CG.translation().z();
  const double hole_m2 = cv::countNonZero(out.object_id == background_id) * (z_m / intrinsics[0]) *
                         (z_m / intrinsics[1]);
  // The hole spans ~1700-4500 px; pixel quantization along the outline (worst when an edge runs
  // along a row of pixel centres) gave 0.02 % (ellipse) to 1.9 % (triangle).
  EXPECT_NEAR(hole_m2, expected_m2, 0.05 * expected_m2) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(FiveKinds, GapFlytShapeTest,
                         ::testing::Values("ellipse", "polygon", "triangle", "notched", "star"));

// RectangleFootprint of a box on the ground: centre, yaw-only rotation, half extents.
struct RectangleFootprint {
  std::string name;
  Eigen::Vector2d center;
  Eigen::Matrix2d R;
  Eigen::Vector2d half;
};

// Separating-axis test of two oriented rectangles.
bool Overlap(const RectangleFootprint& a, const RectangleFootprint& b) {
  for (const RectangleFootprint* f : {&a, &b}) {
    for (int axis = 0; axis < 2; ++axis) {
      const Eigen::Vector2d n = f->R.col(axis);
      const auto reach = [&](const RectangleFootprint& g) {
        return g.half.x() * std::abs(n.dot(g.R.col(0))) + g.half.y() * std::abs(n.dot(g.R.col(1)));
      };
      if (std::abs(n.dot(b.center - a.center)) > reach(a) + reach(b)) return false;
    }
  }
  return true;
}

// Seed 001 D.3.3: origin tag, goal, ground robot, fixed and movable obstacles in their configured
// counts, each with its own tag centred on its top face, inside the area without overlaps, and
// visible where they project in a downward frame from 4 m above the area's centre.
TEST(TagsScenarioTest, AreaHoldsEveryTaggedObjectKind) {
  for (const int seed : {0, 1, 2}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Scenario scenario =
        BuildScenario(LoadScenario("tags", {"seed=" + std::to_string(seed),
                                            "tags.fixed_obstacles=2", "tags.movable_obstacles=4"}));
    const TagsSceneParams& t = scenario.params().tags;
    const Scene& scene = scenario.scene();
    struct Tagged {
      std::string name;
      int tag_id;
      Eigen::Vector3d size_m;
      double tag_size_m;
    };
    std::vector<Tagged> tagged{{"goal", 1, t.goal_size_m, t.tag_size_m},
                               {"robot", 2, t.robot_size_m, t.tag_size_m}};
    for (int k = 0; k < 2; ++k) {
      tagged.push_back({"fixed" + std::to_string(k), 3 + k, t.fixed_size_m, t.tag_size_m});
    }
    for (int k = 0; k < 4; ++k) {
      tagged.push_back(
          {"movable" + std::to_string(k), 5 + k, t.movable_size_m, t.movable_tag_size_m});
    }
    EXPECT_EQ(scene.FindId("fixed2"), -1);
    EXPECT_EQ(scene.FindId("movable4"), -1);
    EXPECT_EQ(scene.FindId("tag9"), -1);
    const Eigen::Vector3d p_origin = scene.object("tag0").T_WO.translation();
    EXPECT_LT(p_origin.norm(), 0.002);  // on the ground at the world origin
    // The movable cubes are light enough for the youBot gripper (D.3.2) and smaller than the
    // fixed obstacles; the kinds have different colours.
    EXPECT_LT(t.movable_size_m.prod(), t.fixed_size_m.prod());
    EXPECT_NE(scene.object("fixed0").material.color, scene.object("movable0").material.color);

    const double origin_half = std::get<Rectangle>(scene.object("tag0").primitive).size_m.x() / 2;
    std::vector<RectangleFootprint> footprints{{"tag0", Eigen::Vector2d::Zero(),
                                                Eigen::Matrix2d::Identity(),
                                                Eigen::Vector2d::Constant(origin_half)}};
    for (const Tagged& object : tagged) {
      SCOPED_TRACE(object.name);
      const SceneObject& box = scene.object(object.name);
      ASSERT_TRUE(std::holds_alternative<Box>(box.primitive));
      EXPECT_EQ(std::get<Box>(box.primitive).size_m, object.size_m);
      const Eigen::Vector3d p_WO = box.T_WO.translation();
      EXPECT_NEAR(p_WO.z(), object.size_m.z() / 2, 1e-12);  // resting on the ground
      const SceneObject& tag = scene.object("tag" + std::to_string(object.tag_id));
      const Eigen::Vector3d p_WT = tag.T_WO.translation();
      EXPECT_NEAR(p_WT.z(), object.size_m.z(), 0.002);  // on the top face (1 mm lift)
      EXPECT_LT((p_WT - p_WO).head<2>().norm(), 1e-9);  // centred
      EXPECT_TRUE(tag.T_WO.linear().col(2).isApprox(-Eigen::Vector3d::UnitZ(), 1e-12));
      const double pattern_m = std::get<Rectangle>(tag.primitive).size_m.x();
      EXPECT_NEAR(pattern_m, AprilTagPatternSize(t.family, object.tag_size_m), 1e-12);
      EXPECT_LE(pattern_m, object.size_m.head<2>().minCoeff());  // the tag fits on the top
      RectangleFootprint footprint{object.name, p_WO.head<2>(),
                                   box.T_WO.linear().topLeftCorner<2, 2>(),
                                   object.size_m.head<2>() / 2};
      for (int corner = 0; corner < 4; ++corner) {
        const Eigen::Vector2d sign(corner % 2 ? 1 : -1, corner / 2 ? 1 : -1);
        const Eigen::Vector2d c =
            footprint.center + footprint.R * footprint.half.cwiseProduct(sign);
        EXPECT_TRUE((c.array() >= 0.0).all() && (c.array() <= t.area_m.array()).all())
            << c.transpose();
      }
      footprints.push_back(footprint);
    }
    for (size_t i = 0; i < footprints.size(); ++i) {
      for (size_t j = i + 1; j < footprints.size(); ++j) {
        EXPECT_FALSE(Overlap(footprints[i], footprints[j]))
            << footprints[i].name << " overlaps " << footprints[j].name;
      }
    }

    // Downward frame (640 x 480, 90 deg) from 4 m above the centre sees the whole area: each tag
    // at its centre, each object on its top face's margin beside the tag.
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.translation() << t.area_m.x() / 2, t.area_m.y() / 2, 4.0;
    const RenderOutput out = RenderAt(scenario, T_WB);
    const ScenarioCamera& camera = scenario.render_camera();
    const Eigen::Isometry3d T_CW = camera.T_WC(T_WB).inverse();
    const auto name_at = [&](const Eigen::Vector3d& p_W) -> std::string {
      Eigen::Vector2d px;
      if (!camera.model->Project(T_CW * p_W, &px) || !camera.model->IsInImage(px, 1.0)) return "";
      const int id = out.object_id.at<int>(
          cv::Point(static_cast<int>(std::lround(px.x())), static_cast<int>(std::lround(px.y()))));
      return id > 0 ? scene.object(id).name : "sky";
    };
    EXPECT_EQ(name_at(p_origin), "tag0");
    for (const Tagged& object : tagged) {
      const SceneObject& box = scene.object(object.name);
      const std::string tag_name = "tag" + std::to_string(object.tag_id);
      EXPECT_EQ(name_at(scene.object(tag_name).T_WO.translation()), tag_name);
      // Mid-way between the tag pattern's edge and the box's edge along x_O, on the top face.
      const double half_pattern = AprilTagPatternSize(t.family, object.tag_size_m) / 2;
      const double margin_x = 0.5 * (half_pattern + object.size_m.x() / 2);
      EXPECT_EQ(name_at(box.T_WO * Eigen::Vector3d(margin_x, 0.0, object.size_m.z() / 2)),
                object.name);
    }
  }
}

// The gap scenario is what the seed-000 detector is built for: along the default approach the
// detector (default parameters = the scenario's default pattern) finds the gap in the captured,
// noisy frames and its pose matches the scene's ground truth T_CG = T_WC^-1 * T_WG.
TEST(GapScenarioTest, DetectorRecoversGroundTruthAlongTheApproach) {
  ScenarioParams params = LoadScenario("gap");
  params.cameras.front().second.supersampling = 1;
  Scenario scenario = BuildScenario(params);
  const ScenarioCamera& camera = scenario.render_camera();
  const KinematicTrajectory trajectory(params.trajectory, scenario.T_WB_start(), params.seed);
  perception::GapDetector detector(perception::GapDetectorParams{}, camera.model);
  RayCaster caster;
  for (const double s : {0.0, 0.3, 0.6}) {  // 4.9, 3.7, 2.5 m from the gap
    const Eigen::Isometry3d T_WC = camera.T_WC(trajectory.T_WB(s));
    const CapturedFrame frame = camera.effects.Capture(
        caster, scenario.scene(), *camera.model, [&](double) { return T_WC; }, s, 0, camera.render);
    const perception::GapDetection detection = detector.DetectFullImage(frame.frame.image);
    ASSERT_TRUE(detection.detected()) << "s = " << s;
    const Eigen::Isometry3d T_CG = T_WC.inverse() * scenario.scene().object("gap").T_WO;
    const double distance_m = T_CG.translation().norm();
    const double error_m = (detection.T_CG.translation() - T_CG.translation()).norm();
    // Monocular pose error grows with distance (seed 000: quadratic); 2 % of the distance bounds
    // it up to 5 m (measured 0.7 % at 4.9 m, 0.3 % at 3.7 m, 0.2 % at 2.5 m).
    EXPECT_LT(error_m, 0.02 * distance_m) << "s = " << s;
  }
}

TEST(GapScenarioTest, DefaultPatternIsTheDetectorsDefault) {
  const GapParams gap = LoadScenario("gap").gap;
  const perception::GapDetectorParams detector;
  EXPECT_EQ(gap.opening_m, detector.opening_size_m);
  EXPECT_EQ(gap.pattern_inner_m, detector.inner_size_m);
  EXPECT_EQ(gap.pattern_outer_m, detector.outer_size_m);
}

TEST(ScenarioLoadTest, UnknownKeyNamesFileLineAndKey) {
  const TempFile file("scenario_typo", "seed: 3\ngap:\n  rol_deg: 30\n");
  try {
    LoadScenario("gap", {}, {file.path()});
    FAIL() << "unknown key accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr(file.path() + ":3:3"), HasSubstr("gap.rol_deg"),
                                HasSubstr("roll_deg")));
  }
}

TEST(ScenarioLoadTest, SectionOfAnotherKindIsRejected) {
  EXPECT_THROW(LoadScenario("gap", {"forest.trees=3"}), std::invalid_argument);
}

TEST(ScenarioLoadTest, BadValuesNameTheKey) {
  EXPECT_THAT(
      [] {
        try {
          LoadScenario("gap", {"cameras.front.model=fisheye"});
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      }(),
      AllOf(HasSubstr("cameras.front.model"), HasSubstr("equidistant")));
  EXPECT_THROW(LoadScenario("gap", {"gap.pattern_inner_m=[0.7, 0.2]"}), std::invalid_argument);
  EXPECT_THROW(LoadScenario("nope"), std::invalid_argument);
}

TEST(ScenarioLoadTest, LedConfigFileSetsTheLeds) {
  const TempFile file("leds",
                      "leds: [[0.2, 0, 0], [0, 0.2, 0], [-0.2, 0, 0], [0, -0.2, 0], "
                      "[0.1, 0.1, -0.05]]\n");
  Scenario scenario = BuildScenario(LoadScenario("led", {"led.config=" + file.path()}));
  ASSERT_EQ(scenario.params().led.leds_B.size(), 5u);
  EXPECT_GE(scenario.scene().FindId("led4"), 1);
  // Attached objects follow the vehicle: led4 sits at T_WB * p_B.
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T_WB.translation() = Eigen::Vector3d(0.3, -0.2, 2.4);
  scenario.SetVehiclePose(T_WB);
  EXPECT_TRUE(scenario.scene().object("led4").T_WO.translation().isApprox(
      T_WB * Eigen::Vector3d(0.1, 0.1, -0.05), 1e-12));
  EXPECT_TRUE(scenario.scene().object("led_target").T_WO.isApprox(T_WB, 1e-12));
}

// One LED loader (perception::LedConfiguration): a file and inline `led.leds` get its checks, which
// are stronger than a count (coplanar or symmetric layouts make the pose ambiguous).
TEST(ScenarioLoadTest, LedLayoutsGetTheLedConfigurationChecks) {
  const auto message = [](const std::vector<std::string>& sets) {
    try {
      LoadScenario("led", sets);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // Five LEDs on one plane: enough of them, but coplanar.
  EXPECT_THAT(message({"led.leds=[[0.2, 0, 0], [0, 0.2, 0], [-0.2, 0, 0], [0, -0.2, 0], "
                       "[0.1, 0.1, 0]]"}),
              AllOf(HasSubstr("led.leds"), HasSubstr("coplanar")));
  // A regular tetrahedron: every relabelling is a rotation.
  const TempFile file("symmetric_leds",
                      "leds: [[0.1, 0.1, 0.1], [0.1, -0.1, -0.1], [-0.1, 0.1, -0.1], "
                      "[-0.1, -0.1, 0.1]]\n");
  EXPECT_THAT(message({"led.config=" + file.path()}),
              AllOf(HasSubstr(file.path()), HasSubstr("symmetric")));
  EXPECT_THROW(LoadScenario("led", {"led.config=" + file.path() + ".missing"}), std::runtime_error);
}

TEST(ScenarioLoadTest, LedFalseSpotsAreSeededEmittersInTheArea) {
  const Scenario a = BuildScenario(LoadScenario("led", {"led.false_spots=3", "seed=4"}));
  const Scenario b = BuildScenario(LoadScenario("led", {"led.false_spots=3", "seed=4"}));
  const LedSceneParams& led = a.params().led;
  for (int k = 0; k < 3; ++k) {
    const std::string name = "false_spot" + std::to_string(k);
    const Eigen::Vector3d p = a.scene().object(name).T_WO.translation();
    EXPECT_EQ(p, b.scene().object(name).T_WO.translation());
    EXPECT_TRUE(std::holds_alternative<Led>(a.scene().object(name).primitive));
    EXPECT_LE(std::abs(p.x()), led.false_spot_area_m.x() / 2);
    EXPECT_LE(std::abs(p.y()), led.false_spot_area_m.y() / 2);
    EXPECT_EQ(p.z(), led.false_spot_height_m);
  }
  EXPECT_EQ(a.scene().FindId("false_spot3"), -1);
}

// objects.<name>.ellipse_holes: [x, y, semi_x, semi_y, angle_deg] cuts a rotated elliptic hole in
// a rectangle: rays through the centre and along the major axis pass, rays beyond the minor axis
// hit the rectangle.
TEST(ScenarioLoadTest, ObjectEllipseHolesAreCut) {
  // A 1 x 1 m rectangle 1 m in front of the start's camera, z_O along +x_W (like T_BC's z_C).
  const TempFile file("ellipse_object",
                      "objects:\n"
                      "  plate:\n"
                      "    shape: rectangle\n"
                      "    size_m: [1.0, 1.0, 0]\n"
                      "    pose: {p_m: [1.1, 0.0, 1.5], rpy_deg: [-90, 0, -90]}\n"
                      "    ellipse_holes: [[0.2, 0.0, 0.15, 0.06, 30]]\n");
  ScenarioParams params = LoadScenario("gap", {}, {file.path()});
  params.cameras.front().second.width = 376;
  params.cameras.front().second.height = 240;
  Scenario scenario = BuildScenario(params);
  const SceneObject& plate = scenario.scene().object("plate");
  const Rectangle& rectangle = std::get<Rectangle>(plate.primitive);
  ASSERT_EQ(rectangle.ellipse_holes.size(), 1u);
  EXPECT_NEAR(rectangle.ellipse_holes[0].angle_rad, 30.0 * M_PI / 180.0, 1e-12);
  const RenderOutput out = RenderAt(scenario, scenario.T_WB_start());
  const ScenarioCamera& camera = scenario.render_camera();
  const Eigen::Isometry3d T_CO = camera.T_WC(scenario.T_WB_start()).inverse() * plate.T_WO;
  const int plate_id = scenario.scene().FindId("plate");
  const auto id_at = [&](const Eigen::Vector2d& xy_O) {
    return IdAt(out, camera, T_CO * Eigen::Vector3d(xy_O.x(), xy_O.y(), 0.0));
  };
  const Eigen::Vector2d centre(0.2, 0.0);
  const Eigen::Vector2d major(std::cos(M_PI / 6), std::sin(M_PI / 6));
  const Eigen::Vector2d minor(-major.y(), major.x());
  EXPECT_NE(id_at(centre), plate_id);
  EXPECT_NE(id_at(centre + 0.11 * major), plate_id);  // inside: semi-major 0.15
  EXPECT_EQ(id_at(centre + 0.11 * minor), plate_id);  // outside: semi-minor 0.06
  EXPECT_EQ(id_at(Eigen::Vector2d(-0.2, 0.0)), plate_id);
  EXPECT_THROW(LoadScenario("gap", {"objects.crate.shape=box",
                                    "objects.crate.ellipse_holes=[[0, 0, 0.1, 0.1, 0]]"}),
               std::invalid_argument);
}

// Image hash of a captured frame at a small resolution; `noise` false: no read or shot noise, so
// the image depends only on the scene.
std::size_t FrameHash(const std::string& name, int seed, bool noise = true) {
  ScenarioParams params = LoadScenario(name, {"seed=" + std::to_string(seed)});
  CameraParams& c = params.cameras.front().second;
  c.width = 188;
  c.height = 120;
  c.supersampling = 1;
  if (!noise) {
    c.read_noise_sigma = 0.0;
    c.full_well_electrons = 0.0;
  }
  Scenario scenario = BuildScenario(params);
  const ScenarioCamera& camera = scenario.render_camera();
  RayCaster caster;
  const CapturedFrame frame = camera.effects.Capture(
      caster, scenario.scene(), *camera.model,
      [&](double) { return camera.T_WC(scenario.T_WB_start()); }, 0.0, 0, camera.render);
  const cv::Mat& image = frame.frame.image;
  return std::hash<std::string>{}(
      std::string(reinterpret_cast<const char*>(image.data), image.total() * image.elemSize()));
}

TEST(ScenarioSeedTest, SameSeedSameImageOtherSeedOtherImage) {
  for (const std::string name : {"gap", "forest"}) {
    EXPECT_EQ(FrameHash(name, 7), FrameHash(name, 7)) << name;
    EXPECT_NE(FrameHash(name, 7), FrameHash(name, 8)) << name;
  }
}

// With the sensor noise off and no pose or light jitter, the seed reaches the image only through
// the procedural textures: another seed gives another image, the same seed the same one.
TEST(ScenarioSeedTest, SeedChangesTexturesWithNoiseOff) {
  EXPECT_EQ(FrameHash("gap", 7, false), FrameHash("gap", 7, false));
  EXPECT_NE(FrameHash("gap", 7, false), FrameHash("gap", 8, false));
}

TEST(ScenarioSeedTest, LightSigmaJittersTheLightingPerSeed) {
  const auto lighting = [](int seed, double sigma) {
    return BuildScenario(LoadScenario("gap", {"seed=" + std::to_string(seed),
                                              "randomize.light_sigma=" + std::to_string(sigma)}))
        .scene()
        .lighting;
  };
  const auto same = [](const Lighting& a, const Lighting& b) {
    return a.ambient == b.ambient && a.directional == b.directional &&
           a.direction_W == b.direction_W;
  };
  // sigma 0: the configured lighting (built-in gap: ambient 0.45, directional 0.55).
  const Lighting nominal = lighting(5, 0.0);
  EXPECT_FLOAT_EQ(nominal.ambient, 0.45f);
  EXPECT_FLOAT_EQ(nominal.directional, 0.55f);
  EXPECT_TRUE(same(nominal, lighting(6, 0.0)));
  const Lighting a = lighting(5, 0.2);
  EXPECT_TRUE(same(a, lighting(5, 0.2)));
  EXPECT_FALSE(same(a, lighting(6, 0.2)));
  EXPECT_NE(a.ambient, nominal.ambient);
  EXPECT_NE(a.directional, nominal.directional);
  EXPECT_GT(std::acos(std::clamp(a.direction_W.normalized().dot(nominal.direction_W.normalized()),
                                 -1.0, 1.0)),
            1e-4);
}

// randomize.yaw_sigma_deg turns a randomizable object about z_W only (its position is kept when
// position_sigma_m is 0), reproducibly per seed.
TEST(ScenarioSeedTest, YawSigmaTurnsObjectsAboutZWorld) {
  const std::vector<std::string> sets{"randomize.yaw_sigma_deg=5", "seed=5"};
  const Eigen::Isometry3d T_a = BuildScenario(LoadScenario("gap", sets)).scene().object("gap").T_WO;
  const Eigen::Isometry3d T_b = BuildScenario(LoadScenario("gap", sets)).scene().object("gap").T_WO;
  const Eigen::Isometry3d T_nominal = BuildScenario(LoadScenario("gap")).scene().object("gap").T_WO;
  EXPECT_EQ(T_a.matrix(), T_b.matrix());
  EXPECT_TRUE(T_a.translation().isApprox(T_nominal.translation(), 1e-12));
  const Eigen::AngleAxisd delta(T_a.linear() * T_nominal.linear().transpose());
  EXPECT_GT(delta.angle(), 1e-6);
  EXPECT_LT(delta.angle(), 5.0 * 5.0 * M_PI / 180.0);  // within 5 sigma
  EXPECT_NEAR(std::abs(delta.axis().z()), 1.0, 1e-9);
  const Eigen::Isometry3d T_other =
      BuildScenario(LoadScenario("gap", {"randomize.yaw_sigma_deg=5", "seed=6"}))
          .scene()
          .object("gap")
          .T_WO;
  EXPECT_FALSE(T_other.isApprox(T_a, 1e-9));
}

TEST(ScenarioSeedTest, RandomizationMovesObjectsReproducibly) {
  const std::vector<std::string> sets{"randomize.position_sigma_m=0.2", "seed=5"};
  const Scenario a = BuildScenario(LoadScenario("gap", sets));
  const Scenario b = BuildScenario(LoadScenario("gap", sets));
  const Scenario nominal = BuildScenario(LoadScenario("gap"));
  const Eigen::Vector3d p_a = a.scene().object("gap").T_WO.translation();
  EXPECT_EQ(p_a, b.scene().object("gap").T_WO.translation());
  EXPECT_GT((p_a - nominal.scene().object("gap").T_WO.translation()).norm(), 1e-6);
}

TEST(KinematicTrajectoryTest, KindsFollowTheirDefinition) {
  TrajectoryParams params;
  Eigen::Isometry3d T_start = Eigen::Isometry3d::Identity();
  T_start.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_start.translation() = Eigen::Vector3d(1, 2, 1.5);
  params.end_p_m = Eigen::Vector3d(5, 2, 1.0);
  for (const std::string kind : {"hover", "line", "circle", "scan", "random"}) {
    params.kind = kind;
    const KinematicTrajectory trajectory(params, T_start, 3);
    EXPECT_TRUE(trajectory.T_WB(0.0).isApprox(T_start, 1e-12)) << kind << " starts at the start";
  }
  params.kind = "line";
  EXPECT_TRUE(
      KinematicTrajectory(params, T_start, 3).T_WB(1.0).translation().isApprox(params.end_p_m));
  EXPECT_TRUE(KinematicTrajectory(params, T_start, 3)
                  .T_WB(0.5)
                  .translation()
                  .isApprox(Eigen::Vector3d(3, 2, 1.25)));
  params.kind = "scan";  // a quarter period out: one amplitude along body y
  params.amplitude_m = 0.3;
  const Eigen::Vector3d lateral =
      KinematicTrajectory(params, T_start, 3).T_WB(0.25).translation() -
      (T_start.translation() + 0.25 * (params.end_p_m - T_start.translation()));
  EXPECT_TRUE(lateral.isApprox(0.3 * T_start.linear().col(1), 1e-12));
  params.kind = "circle";
  params.center_p_m = Eigen::Vector3d(0, 0, 0);
  params.arc_deg = 90.0;
  const Eigen::Isometry3d end = KinematicTrajectory(params, T_start, 3).T_WB(1.0);
  EXPECT_NEAR(end.translation().head<2>().norm(), T_start.translation().head<2>().norm(), 1e-12);
  EXPECT_NEAR(end.translation().head<2>().dot(T_start.translation().head<2>()), 0.0, 1e-12);
  EXPECT_NEAR(end.translation().z(), 1.5, 1e-12);
}

TEST(GroundTruthImagesTest, DepthInMillimetresAndIds) {
  cv::Mat depth(1, 5, CV_32FC1);
  depth.at<float>(0) = 1.2344f;
  depth.at<float>(1) = 1.2346f;
  depth.at<float>(2) = std::numeric_limits<float>::infinity();
  depth.at<float>(3) = 70.0f;
  depth.at<float>(4) = std::numeric_limits<float>::quiet_NaN();
  const cv::Mat mm = DepthToMillimetres16U(depth);
  EXPECT_EQ(mm.at<std::uint16_t>(0), 1234);
  EXPECT_EQ(mm.at<std::uint16_t>(1), 1235);
  EXPECT_EQ(mm.at<std::uint16_t>(2), 0);
  EXPECT_EQ(mm.at<std::uint16_t>(3), 65535);
  EXPECT_EQ(mm.at<std::uint16_t>(4), 0);
  cv::Mat ids = (cv::Mat_<int>(1, 3) << 0, 7, 70000);
  const cv::Mat ids16 = ObjectIdsTo16U(ids);
  EXPECT_EQ(ids16.at<std::uint16_t>(1), 7);
  EXPECT_EQ(ids16.at<std::uint16_t>(2), 65535);
  EXPECT_THROW(DepthToMillimetres16U(ids), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::sim
