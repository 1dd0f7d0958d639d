// The tag front end on the simulator's `tags` scenario (ray-traced tags, sensor noise) against
// the scene's ground truth: corners where the true tag corners project (this pins the apriltag
// library's half-pixel convention), poses within centimetres, through a pinhole and a 180 deg
// equidistant fisheye (corners undistorted through the camera model).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "control/so3.h"
#include "perception/tags/apriltag_library_detector.h"
#include "perception/tags/tag_front_end.h"
#include "sim/scenario/scenario.h"

namespace aperture::sim {
namespace {

struct TagSceneCase {
  const char* name;
  std::vector<std::string> sets;
  double max_translation_error_m;  // per metre of distance
};

// The apriltag front end with the scenario's tag sizes, quads found at full resolution.
perception::TagFrontEnd MakeFrontEnd(const Scenario& scenario, const ScenarioCamera& camera) {
  perception::TagFrontEndParams params;
  const TagsSceneParams& tags = scenario.params().tags;
  params.size_m = tags.tag_size_m;
  const int first_movable = 3 + tags.fixed_obstacles;
  for (int k = 0; k < tags.movable_obstacles; ++k) {
    params.sizes[first_movable + k] = tags.movable_tag_size_m;
  }
  params.detection.quad_decimate = 1.0;
  return perception::TagFrontEnd(
      std::make_unique<perception::AprilTagLibraryDetector>(params.detection), camera.model,
      params);
}

class AprilTagSceneTest : public ::testing::TestWithParam<TagSceneCase> {};

TEST_P(AprilTagSceneTest, DetectsEveryVisibleTagAtItsTruePose) {
  std::vector<std::string> sets = GetParam().sets;
  // Over the middle of the field at 2.5 m (the tags scenario's default camera looks down).
  sets.push_back("vehicle.start.p_m=[2.0, 3.0, 2.5]");
  Scenario scenario = BuildScenario(LoadScenarioParams(ScenarioConfig("tags", {}, sets)));
  const ScenarioCamera& camera = scenario.camera("down");
  const Eigen::Isometry3d T_WC = camera.T_WC(scenario.T_WB_start());
  RayCaster caster;
  const CapturedFrame captured = camera.effects.Capture(
      caster, scenario.scene(), *camera.model, [&](double) { return T_WC; }, 0.0, 0, camera.render);

  perception::TagFrontEnd front_end = MakeFrontEnd(scenario, camera);
  const perception::TagFrameResult result = front_end.Process(captured.frame.image, 0.0);
  const int first_movable = 3 + scenario.params().tags.fixed_obstacles;
  const double size_m = scenario.params().tags.tag_size_m;
  // Every 0.25 m tag within 50 deg of the optical axis whose corners all project 5 px inside the
  // image is detected (nearer the fisheye's rim the tags are squeezed to a few pixels across).
  const int tag_count = first_movable + scenario.params().tags.movable_obstacles;
  int visible = 0;
  for (int id = 0; id < first_movable; ++id) {
    const Eigen::Isometry3d T_CT =
        T_WC.inverse() * scenario.scene().object("tag" + std::to_string(id)).T_WO;
    bool inside = T_CT.translation().normalized().z() > std::cos(50.0 * M_PI / 180.0);
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector2d px;
      inside = inside && camera.model->Project(T_CT * perception::TagCorner(k, size_m), &px) &&
               px.x() > 5 && px.y() > 5 && px.x() < camera.model->width() - 5 &&
               px.y() < camera.model->height() - 5;
    }
    if (!inside) continue;
    ++visible;
    EXPECT_TRUE(
        std::any_of(result.tags.begin(), result.tags.end(),
                    [&](const perception::TagResult& tag) { return tag.detection.id == id; }))
        << GetParam().name << ": visible tag " << id << " not detected";
  }
  ASSERT_GE(visible, 2) << GetParam().name;
  ASSERT_LE(static_cast<int>(result.tags.size()), tag_count);
  double corner_error_sum = 0.0;
  int corners = 0;
  for (const perception::TagResult& tag : result.tags) {
    const int object = scenario.scene().FindId("tag" + std::to_string(tag.detection.id));
    ASSERT_GE(object, 0) << "detected id " << tag.detection.id << " is not in the scene";
    const Eigen::Isometry3d T_CT = T_WC.inverse() * scenario.scene().object(object).T_WO;
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector2d px;
      ASSERT_TRUE(camera.model->Project(T_CT * perception::TagCorner(k, tag.size_m), &px));
      corner_error_sum += (px - tag.detection.corners_px[k]).norm();
      ++corners;
    }
    ASSERT_TRUE(tag.pose);
    const double distance_m = T_CT.translation().norm();
    const perception::TagPoseCandidate* nearest = &tag.pose->best;
    auto angle_deg = [&](const perception::TagPoseCandidate& c) {
      return control::LogSo3(c.T_CT.linear().transpose() * T_CT.linear()).norm() * 180 / M_PI;
    };
    if (tag.pose->alternative && angle_deg(*tag.pose->alternative) < angle_deg(*nearest)) {
      nearest = &*tag.pose->alternative;
    }
    EXPECT_LT((nearest->T_CT.translation() - T_CT.translation()).norm(),
              GetParam().max_translation_error_m * distance_m)
        << GetParam().name << " tag " << tag.detection.id;
    EXPECT_LT(angle_deg(*nearest), 4.0) << GetParam().name << " tag " << tag.detection.id;
  }
  // Sub-pixel corners: a half-pixel convention error would show as ~0.7 px.
  EXPECT_LT(corner_error_sum / corners, 0.3) << GetParam().name;
}

// Sub-pixel edges in the scenario's camera (supersampling): the origin tag seen from 2.45 m,
// its edges parallel to the pixel rows as in the mapping flight, while the camera slides by
// 1/8 px steps. Detected corners must follow the motion: with one ray per pixel every edge snaps
// to a pixel border, the corners stay put for a pixel and then jump, and the tag looks up to a
// pixel larger or smaller (a 32 px tag: depth off by up to 3 %). In the mapping flight that
// error did not average out, since the sub-pixel phase across a lane is the same in every frame:
// the whole map shifted against the origin tag (issue 15). A 160 x 120 crop of the down camera
// (same focal length) keeps the test fast.
TEST(AprilTagScene, CornersFollowSubPixelMotion) {
  const double f_px = 320.0;  // the tags scenario's 640 px, 90 deg camera
  const double fov_deg = 2.0 * std::atan(80.0 / f_px) * 180.0 / M_PI;
  Scenario scenario = BuildScenario(
      LoadScenarioParams(ScenarioConfig("tags", {},
                                        {"cameras.down.width=160", "cameras.down.height=120",
                                         "cameras.down.fov_deg=" + std::to_string(fov_deg)})));
  const ScenarioCamera& camera = scenario.camera("down");
  perception::TagFrontEnd front_end = MakeFrontEnd(scenario, camera);
  const Eigen::Isometry3d T_W0 = scenario.scene().object("tag0").T_WO;
  RayCaster caster;
  double squared_error_sum_px2 = 0.0;
  int corners = 0;
  const double height_m = 2.5;
  const double pixel_m = (height_m - 0.05) / f_px;  // at the tag
  for (int k = 0; k < 8; ++k) {
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T_WB.translation() = Eigen::Vector3d(0.1 + k * pixel_m / 8, 0.05 + k * pixel_m / 8, height_m);
    const Eigen::Isometry3d T_WC = camera.T_WC(T_WB);
    const CapturedFrame captured = camera.effects.Capture(
        caster, scenario.scene(), *camera.model, [&](double) { return T_WC; }, 0.0, k,
        camera.render);
    const perception::TagFrameResult result = front_end.Process(captured.frame.image, 0.0);
    const auto origin =
        std::find_if(result.tags.begin(), result.tags.end(),
                     [](const perception::TagResult& tag) { return tag.detection.id == 0; });
    ASSERT_NE(origin, result.tags.end()) << "frame " << k;
    const Eigen::Isometry3d T_CT = T_WC.inverse() * T_W0;
    for (int c = 0; c < 4; ++c) {
      Eigen::Vector2d px;
      ASSERT_TRUE(camera.model->Project(
          T_CT * perception::TagCorner(c, scenario.params().tags.tag_size_m), &px));
      squared_error_sum_px2 += (px - origin->detection.corners_px[c]).squaredNorm();
      ++corners;
    }
  }
  // Measured: 0.45 px with one ray per pixel, 0.20 px with the scenario's 3 x 3 (the rest: the
  // library's edge refinement on edges parallel to the pixel rows).
  EXPECT_LT(std::sqrt(squared_error_sum_px2 / corners), 0.3);
}

INSTANTIATE_TEST_SUITE_P(
    Cameras, AprilTagSceneTest,
    ::testing::Values(TagSceneCase{"pinhole", {}, 0.01},
                      TagSceneCase{"fisheye",
                                   {"cameras.down.model=equidistant", "cameras.down.fov_deg=180",
                                    "cameras.down.distortion=[0.02, -0.005, 0.0, 0.0]"},
                                   0.03}),  // tags near the 180 deg lens' rim, ~55 deg off axis
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace aperture::sim
