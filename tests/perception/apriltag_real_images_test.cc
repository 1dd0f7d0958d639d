// The tag front end on real and reference images: Debian's visp-images-data (ViSP-images/
// AprilTag). Skips, saying why, when the package is not installed (scripts/install-deps.sh
// installs it).
//   AprilTag.pgm             a photo of 12 tag36h11 tags (ids 8-19) with ViSP's reference poses
//                            (ground_truth_pose.txt: tx ty tz [m], theta-u [rad]; camera and tag
//                            size from ViSP's testAprilTag.cpp: fx 615.1674805, fy 615.1675415,
//                            cx 312.1889954, cy 243.4373779, no distortion, 0.053 m tags)
//   benchmark/640x480/       5 rendered tags (ids 0-4) per family with reference corners and
//                            poses cMo_<id>.txt (ViSP's catchAprilTag.cpp: fx = fy = 700,
//                            cx 320, cy 240; tags 0.25 m (ids 0-2) and 0.125 m (ids 3-4) across
//                            the whole pattern, i.e. times the family's border/total ratio)
//   benchmark/1920x1080/     the same scenes at full HD (no references): detection only
// ViSP's tag frame has z out of the tag (towards the camera); ours (the apriltag library's) z
// into it: T_CT = T_CO(ViSP) * Rx(pi) (catchAprilTag.cpp's z-aligned case).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>
#include <string>

#include "control/so3.h"
#include "perception/camera/pinhole_camera.h"
#include "perception/tags/apriltag_library_detector.h"
#include "perception/tags/tag_pose_estimator.h"
#include "tests/support/rotation_error.h"

namespace aperture::perception {
namespace {

using test_support::RotationErrorDeg;

// ViSP's own lookup: $VISP_INPUT_IMAGE_PATH, else Debian's install location of the package.
std::filesystem::path AprilTagDataDir() {
  const char* env = std::getenv("VISP_INPUT_IMAGE_PATH");
  const std::filesystem::path root = env ? env : "/usr/share/visp-images-data";
  return root / "ViSP-images" / "AprilTag";
}

#define REQUIRE_DATA()                                                                        \
  if (!std::filesystem::exists(AprilTagDataDir() / "AprilTag.pgm")) {                         \
    GTEST_SKIP() << "Debian package visp-images-data not installed (no " << AprilTagDataDir() \
                 << "); run scripts/install-deps.sh or set VISP_INPUT_IMAGE_PATH";            \
  }

Eigen::Isometry3d VispToOurTagFrame(const Eigen::Isometry3d& T_CO) {
  Eigen::Isometry3d T_OT = Eigen::Isometry3d::Identity();
  T_OT.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return T_CO * T_OT;
}

cv::Mat ReadGray(const std::filesystem::path& path) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
  EXPECT_FALSE(image.empty()) << "cannot read " << path;
  return image;
}

// The acceptance of issue 15: every tag of the photo found with its id, translation error
// <= 1 cm against ViSP's reference; rotation errors reported (the reference is ViSP's own
// estimate from the same corners, so the two agree to the refinement's noise).
TEST(AprilTagRealImages, PhotoEveryTagFoundWithinOneCentimetre) {
  REQUIRE_DATA();
  const cv::Mat image = ReadGray(AprilTagDataDir() / "AprilTag.pgm");
  const PinholeCamera camera(640, 480, {615.1674805, 615.1675415, 312.1889954, 243.4373779});
  std::map<int, Eigen::Isometry3d> truth;
  std::ifstream file(AprilTagDataDir() / "ground_truth_pose.txt");
  std::string message;
  double tx, ty, tz, ux, uy, uz;
  while (file >> message >> tx >> ty >> tz >> ux >> uy >> uz) {
    const int id = std::stoi(message.substr(message.rfind('_') + 1));  // "36h11_id:_8"
    Eigen::Isometry3d T_CO = Eigen::Isometry3d::Identity();
    T_CO.linear() = control::ExpSo3(Eigen::Vector3d(ux, uy, uz));
    T_CO.translation() = Eigen::Vector3d(tx, ty, tz);
    truth[id] = VispToOurTagFrame(T_CO);
  }
  ASSERT_EQ(truth.size(), 12u);
  AprilTagLibraryDetector detector(TagDetectorParams{});  // defaults: 36h11, decimate 2
  const std::vector<TagDetection> detections = detector.Detect(image);
  std::map<int, const TagDetection*> by_id;
  for (const TagDetection& detection : detections) by_id[detection.id] = &detection;
  EXPECT_EQ(detections.size(), truth.size()) << "no extra or doubled tags";
  for (const auto& [id, T_CT_true] : truth) {
    ASSERT_TRUE(by_id.count(id)) << "tag " << id << " not found";
    const std::optional<TagPose> pose = EstimateTagPose(camera, by_id[id]->corners_px, 0.053);
    ASSERT_TRUE(pose) << "tag " << id;
    // The candidate nearer the reference (the flip is TagFlipResolver's business).
    const TagPoseCandidate& chosen =
        pose->alternative && RotationErrorDeg(pose->alternative->T_CT, T_CT_true) <
                                 RotationErrorDeg(pose->best.T_CT, T_CT_true)
            ? *pose->alternative
            : pose->best;
    const double translation_error_m = (chosen.T_CT.translation() - T_CT_true.translation()).norm();
    const double rotation_error_deg = RotationErrorDeg(chosen.T_CT, T_CT_true);
    EXPECT_LE(translation_error_m, 0.01) << "tag " << id;
    std::cout << "tag " << id << ": translation error " << translation_error_m * 1000 << " mm, "
              << "rotation error " << rotation_error_deg << " deg (best "
              << RotationErrorDeg(pose->best.T_CT, T_CT_true) << " deg, ambiguity ratio "
              << pose->ambiguity_ratio << ")\n";
    RecordProperty("tag" + std::to_string(id) + "_rotation_error_mdeg",
                   static_cast<int>(rotation_error_deg * 1000));
  }
}

struct BenchmarkFamily {
  const char* family;
  const char* file_tag;    // tag36_11
  double border_fraction;  // black border edge / whole pattern edge
};

constexpr BenchmarkFamily kBenchmarkFamilies[] = {
    {"tag16h5", "tag16_05", 6.0 / 8},          {"tag25h9", "tag25_09", 7.0 / 9},
    {"tag36h11", "tag36_11", 8.0 / 10},        {"tagCircle21h7", "tag21_07", 5.0 / 9},
    {"tagCircle49h12", "tag49_12", 5.0 / 11},  {"tagCustom48h12", "tag48_12", 6.0 / 10},
    {"tagStandard41h12", "tag41_12", 5.0 / 9}, {"tagStandard52h13", "tag52_13", 6.0 / 10},
};

class AprilTagBenchmarkImages : public ::testing::TestWithParam<BenchmarkFamily> {};

// 640 x 480: the five tags of the family with ids 0-4, corners within 0.5 px of the reference
// (ViSP's own tolerance), and poses against cMo_<id>.txt within ViSP's per-tag thresholds
// (translation 2.5-13 cm, these are small rendered tags up to ~2 m away).
TEST_P(AprilTagBenchmarkImages, AllFiveTagsAtVga) {
  REQUIRE_DATA();
  const BenchmarkFamily& family = GetParam();
  const std::filesystem::path dir = AprilTagDataDir() / "benchmark" / "640x480";
  const cv::Mat image = ReadGray(dir / (std::string(family.file_tag) + "_640x480.png"));
  TagDetectorParams params;
  params.families = {family.family};
  params.quad_decimate = 1.0;
  // Exact decoding: clean reference renders, and the big families' decode tables stay small
  // (49h12 with 1 corrected bit takes seconds to build).
  params.max_hamming = 0;
  AprilTagLibraryDetector detector(params);
  const std::vector<TagDetection> detections = detector.Detect(image);
  ASSERT_EQ(detections.size(), 5u) << family.family;
  std::map<int, std::array<Eigen::Vector2d, 4>> reference;
  std::ifstream corners(dir / (std::string("corners_") + family.file_tag + ".txt"));
  int id;
  std::array<Eigen::Vector2d, 4> c;
  while (corners >> id >> c[0].x() >> c[0].y() >> c[1].x() >> c[1].y() >> c[2].x() >> c[2].y() >>
         c[3].x() >> c[3].y()) {
    reference[id] = c;
  }
  const PinholeCamera camera(640, 480, {700.0, 700.0, 320.0, 240.0});
  const double errors_m[5] = {0.025, 0.09, 0.05, 0.13, 0.09};  // catchAprilTag.cpp
  for (const TagDetection& detection : detections) {
    ASSERT_TRUE(reference.count(detection.id)) << family.family << " id " << detection.id;
    for (int k = 0; k < 4; ++k) {
      // The reference is in the library's coordinates (pixel centres at +0.5).
      const Eigen::Vector2d expected = reference[detection.id][k] - Eigen::Vector2d(0.5, 0.5);
      EXPECT_LT((detection.corners_px[k] - expected).norm(), 0.5)
          << family.family << " id " << detection.id << " corner " << k;
    }
    std::ifstream pose_file(dir / ("cMo_" + std::to_string(detection.id) + ".txt"));
    Eigen::Matrix4d M;
    for (int r = 0; r < 4; ++r) {
      for (int col = 0; col < 4; ++col) pose_file >> M(r, col);
    }
    const Eigen::Isometry3d T_CT_true = VispToOurTagFrame(Eigen::Isometry3d(M));
    const double size_m = (detection.id < 3 ? 0.25 : 0.125) * family.border_fraction;
    const std::optional<TagPose> pose = EstimateTagPose(camera, detection.corners_px, size_m);
    ASSERT_TRUE(pose);
    EXPECT_LT((pose->best.T_CT.translation() - T_CT_true.translation()).norm(),
              errors_m[detection.id] * std::sqrt(3.0))  // ViSP's threshold is an RMS per axis
        << family.family << " id " << detection.id;
  }
}

// 1920 x 1080: the same five ids found at the default settings (decimate 2).
TEST_P(AprilTagBenchmarkImages, AllFiveTagsAtFullHd) {
  REQUIRE_DATA();
  const BenchmarkFamily& family = GetParam();
  const cv::Mat image = ReadGray(AprilTagDataDir() / "benchmark" / "1920x1080" /
                                 (std::string(family.file_tag) + "_1920x1080.png"));
  TagDetectorParams params;
  params.families = {family.family};
  params.max_hamming = 0;  // as above
  AprilTagLibraryDetector detector(params);
  std::set<int> ids;
  for (const TagDetection& detection : detector.Detect(image)) ids.insert(detection.id);
  EXPECT_EQ(ids, (std::set<int>{0, 1, 2, 3, 4})) << family.family;
}

INSTANTIATE_TEST_SUITE_P(Families, AprilTagBenchmarkImages, ::testing::ValuesIn(kBenchmarkFamilies),
                         [](const auto& info) { return std::string(info.param.file_tag); });

}  // namespace
}  // namespace aperture::perception
