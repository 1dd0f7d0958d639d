#include "perception/tags/tag_map.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "control/so3.h"
#include "perception/tags/tag_map_writer.h"
#include "temp_directory.h"

namespace aperture::perception {
namespace {

// A paper-D-like field: the origin tag plus 12 tags lying flat (z_T down) at random spots and
// yaws in 4 x 6 m, some on 0.4 m boxes; a downward camera at 2.5 m on a lawn-mower pattern sees
// every tag within 2 m of its nadir (a 90 deg lens sees +-2.5 m). Observations get Gaussian noise
// from a known covariance (5 mm lateral, 15 mm along the ray, 0.5 deg), and `flips` of them are
// replaced by a mirrored-tilt pose (40 deg off: the planar ambiguity's wrong solution).
struct Field {
  std::map<int, Eigen::Isometry3d> T_WT;
  std::vector<std::vector<TagMapObservation>> images;
  int flips = 0;
};

Eigen::Isometry3d Pose(const Eigen::Vector3d& p, double yaw, double roll = M_PI) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = p;
  return T;
}

Field MakeField(std::uint32_t seed, int flip_every) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0.3, 3.7), y(0.3, 5.7), yaw(-M_PI, M_PI);
  Field field;
  field.T_WT[0] = TagMapParams{}.T_W_origin();
  for (int id = 1; id <= 12; ++id) {
    field.T_WT[id] = Pose({x(rng), y(rng), id % 3 == 0 ? 0.4 : 0.0}, yaw(rng));
  }
  Matrix6d covariance = Matrix6d::Zero();
  covariance.diagonal() << 0.005 * 0.005, 0.005 * 0.005, 0.015 * 0.015, std::pow(M_PI / 180, 2),
      std::pow(M_PI / 180, 2), std::pow(M_PI / 180, 2);
  const Eigen::LLT<Matrix6d> llt(covariance);
  std::normal_distribution<double> normal;
  int observation_count = 0;
  // Lawn-mower: lanes along y every 0.7 m, a picture every 0.5 m; start at the far end so the
  // first images do not see the origin (they must wait until the map reaches them).
  std::vector<Eigen::Vector2d> stations;
  for (int lane = 0; lane < 6; ++lane) {
    for (int k = 0; k <= 12; ++k) {
      const double along = lane % 2 ? 6.0 - 0.5 * k : 0.5 * k;
      stations.emplace_back(0.25 + 0.7 * lane, along);
    }
  }
  std::reverse(stations.begin(), stations.end());
  for (const Eigen::Vector2d& xy : stations) {
    const Eigen::Isometry3d T_WC = Pose({xy.x(), xy.y(), 2.5}, yaw(rng));
    std::vector<TagMapObservation> image;
    for (const auto& [id, T_WT] : field.T_WT) {
      if ((T_WT.translation().head<2>() - xy).norm() > 2.0) continue;
      const Eigen::Isometry3d T_CT = T_WC.inverse() * T_WT;
      control::Vector6d noise;
      for (int i = 0; i < 6; ++i) noise(i) = normal(rng);
      const control::Vector6d delta = llt.matrixL() * noise;
      TagMapObservation observation{"tag36h11", id, 0.25, T_CT, covariance};
      observation.T_CT.translation() += delta.head<3>();
      observation.T_CT.linear() = control::ExpSo3(delta.tail<3>()) * T_CT.linear();
      if (flip_every > 0 && ++observation_count % flip_every == 0 && id != 0) {
        observation.T_CT.linear() = control::ExpSo3(Eigen::Vector3d(0.7, 0, 0)) * T_CT.linear();
        ++field.flips;
      }
      image.push_back(observation);
    }
    field.images.push_back(image);
  }
  return field;
}

struct MapErrors {
  double position_rms_m = 0;
  double initial_position_rms_m = 0;
  double max_rotation_error_deg = 0;
};

MapErrors Evaluate(const Field& field, const std::vector<MappedTag>& tags) {
  MapErrors errors;
  for (const MappedTag& tag : tags) {
    const Eigen::Isometry3d& truth = field.T_WT.at(tag.id);
    errors.position_rms_m += (tag.T_WT.translation() - truth.translation()).squaredNorm();
    errors.initial_position_rms_m +=
        (tag.T_WT_initial.translation() - truth.translation()).squaredNorm();
    errors.max_rotation_error_deg =
        std::max(errors.max_rotation_error_deg,
                 control::LogSo3(tag.T_WT.linear().transpose() * truth.linear()).norm() * 180 / M_PI);
  }
  errors.position_rms_m = std::sqrt(errors.position_rms_m / tags.size());
  errors.initial_position_rms_m = std::sqrt(errors.initial_position_rms_m / tags.size());
  return errors;
}

TEST(TagMap, RecoversTheFieldAndBeatsTheChainedInitialisation) {
  const Field field = MakeField(5, 0);
  TagMap map;
  for (std::size_t k = 0; k < field.images.size(); ++k) map.AddImage(0.1 * k, field.images[k]);
  const TagMapSolveSummary summary = map.Optimize();
  EXPECT_TRUE(summary.converged) << summary;
  EXPECT_TRUE(summary.covariance_ok) << summary;
  EXPECT_EQ(map.pending_images(), 0);
  const std::vector<MappedTag> tags = map.Tags();
  ASSERT_EQ(tags.size(), field.T_WT.size());
  const MapErrors errors = Evaluate(field, tags);
  // The chained start accumulates the noise of every hop (a 0.5 deg rotation error moves the next
  // camera by ~2 cm at 2.5 m); the graph averages ~10-20 views per tag. The bound is the
  // issue's map acceptance (2 cm); the per-tag check below holds the optimizer to its own
  // covariance.
  std::cout << "map RMS before " << errors.initial_position_rms_m << " m, after "
            << errors.position_rms_m << " m\n";
  EXPECT_LT(errors.position_rms_m, 0.02);
  EXPECT_LT(errors.position_rms_m, errors.initial_position_rms_m);
  EXPECT_LT(errors.max_rotation_error_deg, 1.0);
  for (const MappedTag& tag : tags) {
    if (tag.id == 0) {
      EXPECT_FALSE(tag.has_covariance);  // the gauge
      EXPECT_TRUE(tag.T_WT.isApprox(field.T_WT.at(0), 1e-12));
      continue;
    }
    ASSERT_TRUE(tag.has_covariance);
    // The error is within 4 sigma of the marginal (chi^2_3 99.9 % is 16.3).
    const Eigen::Vector3d error = tag.T_WT.translation() - field.T_WT.at(tag.id).translation();
    EXPECT_LT(error.dot(tag.covariance.topLeftCorner<3, 3>().ldlt().solve(error)), 16.3) << tag.id;
  }
}

// Every 7th observation is a flipped pose: the robust loss and the chi^2 gate drop them and no
// flipped tag survives into the map.
TEST(TagMap, RejectsFlippedObservations) {
  const Field field = MakeField(11, 7);
  ASSERT_GT(field.flips, 10);
  TagMap map;
  for (std::size_t k = 0; k < field.images.size(); ++k) map.AddImage(0.1 * k, field.images[k]);
  const TagMapSolveSummary summary = map.Optimize();
  const MapErrors errors = Evaluate(field, map.Tags());
  EXPECT_GE(summary.rejected_observations, field.flips * 9 / 10) << summary;
  EXPECT_LT(errors.position_rms_m, 0.03);
  EXPECT_LT(errors.max_rotation_error_deg, 2.0);
}

TEST(TagMap, WritesYamlAndTopView) {
  const Field field = MakeField(5, 0);
  TagMap map;
  for (std::size_t k = 0; k < field.images.size(); ++k) map.AddImage(0.1 * k, field.images[k]);
  map.Optimize();
  const test_support::TempDirectory dir;
  const std::string yaml_path = (dir.path() / "map.yaml").string();
  const std::string png_path = (dir.path() / "map.png").string();
  WriteTagMapYaml(yaml_path, map.Tags(), map.params());
  WriteTagMapTopView(png_path, map.Tags());
  const YAML::Node root = YAML::LoadFile(yaml_path);
  EXPECT_EQ(root["origin_id"].as<int>(), 0);
  ASSERT_EQ(root["tags"].size(), map.Tags().size());
  const MappedTag& tag = map.Tags()[3];
  const YAML::Node node = root["tags"][3];
  EXPECT_EQ(node["id"].as<int>(), tag.id);
  EXPECT_DOUBLE_EQ(node["size_m"].as<double>(), 0.25);
  const auto p = node["T_WT"]["p_m"].as<std::vector<double>>();
  EXPECT_NEAR(p[0], tag.T_WT.translation().x(), 1e-8);
  EXPECT_NEAR(p[2], tag.T_WT.translation().z(), 1e-8);
  EXPECT_EQ(node["covariance"].size(), 36u);
  EXPECT_NEAR(node["covariance"][0].as<double>(), tag.covariance(0, 0),
              1e-10 * tag.covariance(0, 0));  // 12 digits
  const cv::Mat png = cv::imread(png_path);
  ASSERT_FALSE(png.empty());
  EXPECT_GT(png.cols, 4 * 120);  // 4 m field at 120 px/m plus margins
}

TEST(TagMap, RejectsBadObservationsAndParams) {
  TagMap map;
  TagMapObservation observation{"tag36h11", 0, 0.25, Eigen::Isometry3d::Identity(),
                                Matrix6d::Identity()};
  observation.covariance(2, 2) = -1.0;
  EXPECT_THROW(map.AddImage(0.0, {observation}), std::invalid_argument);
  observation.covariance = Matrix6d::Identity();
  observation.tag_size_m = 0.0;
  EXPECT_THROW(map.AddImage(0.0, {observation}), std::invalid_argument);
  TagMapParams params;
  params.outlier_chi2 = 0.0;
  EXPECT_THROW(TagMap{params}, std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
