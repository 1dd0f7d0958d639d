#pragma once
// A tag map against the scene's ground truth, in the origin tag's frame (the map's gauge: an
// error of the origin's own placement is not the map's), for `aperture bench tags` (mapping
// section) and the mapping flight (`aperture sim tags`, experiments/missions/tag_mapping_flight.h):
// per mapped tag the position error after and before optimization (TagMap's chained
// initialisation), the rotation error, and whether it is flipped (rotation more than
// kFlippedTagDeg off: a planar-ambiguity flip, not noise); over the tags the RMS position errors
// and their mean (the common offset against the gauge).
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "perception/tags/tag_map.h"
#include "sim/scene/scene.h"

namespace aperture::experiments {

constexpr double kFlippedTagDeg = 10.0;

// Angle of a.linear()^T b.linear() [deg].
double RotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

struct TagMapError {
  std::string family;
  int id = -1;
  double size_m = 0.0;
  Eigen::Vector3d p_true_m = Eigen::Vector3d::Zero();        // in the origin tag's frame
  Eigen::Vector3d error_m = Eigen::Vector3d::Zero();         // mapped - true
  Eigen::Vector3d error_before_m = Eigen::Vector3d::Zero();  // before optimization
  double rotation_error_deg = 0.0;
  bool flipped = false;
  double sigma_m = 0.0;  // sqrt(trace) of the marginal position covariance (0: none)
  int observations = 0;
  int rejected = 0;
};

struct TagMapEvaluation {
  double rms_before_m = 0.0;
  double rms_after_m = 0.0;
  Eigen::Vector3d mean_error_m = Eigen::Vector3d::Zero();
  int flipped = 0;
  std::vector<TagMapError> tags;  // the mapped tags, in TagMap::Tags() order

  // Per tag: id, error_m [x, y, z], error_before_m (norm), rotation_error_deg, sigma_m,
  // observations, rejected (the bench's "map_tags").
  nlohmann::json PerTagJson() const;
};

// std::invalid_argument when the scene has no object "tag<id>" for a mapped tag or the origin.
TagMapEvaluation EvaluateTagMap(const perception::TagMap& map, const sim::Scene& scene);

}  // namespace aperture::experiments
