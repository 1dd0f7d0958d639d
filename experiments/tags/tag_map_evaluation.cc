#include "experiments/tags/tag_map_evaluation.h"

#include <cmath>
#include <stdexcept>

#include "control/so3.h"

namespace aperture::experiments {
namespace {

const Eigen::Isometry3d& TrueTagPose(const sim::Scene& scene, int id) {
  const std::string name = "tag" + std::to_string(id);
  if (scene.FindId(name) < 0) {
    throw std::invalid_argument("tag map evaluation: the map holds tag " + std::to_string(id) +
                                " but the scene has no object '" + name + "'");
  }
  return scene.object(name).T_WO;
}

}  // namespace

double RotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return control::LogSo3(a.linear().transpose() * b.linear()).norm() * 180.0 / M_PI;
}

nlohmann::json TagMapEvaluation::PerTagJson() const {
  nlohmann::json per_tag = nlohmann::json::array();
  for (const TagMapError& tag : tags) {
    per_tag.push_back({{"id", tag.id},
                       {"error_m", {tag.error_m.x(), tag.error_m.y(), tag.error_m.z()}},
                       {"error_before_m", tag.error_before_m.norm()},
                       {"rotation_error_deg", tag.rotation_error_deg},
                       {"sigma_m", tag.sigma_m},
                       {"observations", tag.observations},
                       {"rejected", tag.rejected}});
  }
  return per_tag;
}

TagMapEvaluation EvaluateTagMap(const perception::TagMap& map, const sim::Scene& scene) {
  TagMapEvaluation evaluation;
  const Eigen::Isometry3d T_W0 = map.params().T_W_origin();
  const Eigen::Isometry3d T_W0_true = TrueTagPose(scene, map.params().origin_id);
  for (const perception::MappedTag& tag : map.Tags()) {
    const Eigen::Isometry3d T_0T_true = T_W0_true.inverse() * TrueTagPose(scene, tag.id);
    const Eigen::Isometry3d T_0T = T_W0.inverse() * tag.T_WT;
    const Eigen::Isometry3d T_0T_before = T_W0.inverse() * tag.T_WT_initial;
    TagMapError error;
    error.family = tag.family;
    error.id = tag.id;
    error.size_m = tag.size_m;
    error.p_true_m = T_0T_true.translation();
    error.error_m = T_0T.translation() - T_0T_true.translation();
    error.error_before_m = T_0T_before.translation() - T_0T_true.translation();
    error.rotation_error_deg = RotationErrorDeg(T_0T, T_0T_true);
    error.flipped = error.rotation_error_deg > kFlippedTagDeg;
    error.sigma_m =
        tag.has_covariance ? std::sqrt(tag.covariance.topLeftCorner<3, 3>().trace()) : 0.0;
    error.observations = tag.observations;
    error.rejected = tag.rejected;
    evaluation.rms_after_m += error.error_m.squaredNorm();
    evaluation.rms_before_m += error.error_before_m.squaredNorm();
    evaluation.mean_error_m += error.error_m;
    evaluation.flipped += error.flipped;
    evaluation.tags.push_back(error);
  }
  if (!evaluation.tags.empty()) {
    const double n = static_cast<double>(evaluation.tags.size());
    evaluation.rms_after_m = std::sqrt(evaluation.rms_after_m / n);
    evaluation.rms_before_m = std::sqrt(evaluation.rms_before_m / n);
    evaluation.mean_error_m /= n;
  }
  return evaluation;
}

}  // namespace aperture::experiments
