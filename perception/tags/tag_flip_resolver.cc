#include "perception/tags/tag_flip_resolver.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "control/so3.h"

namespace aperture::perception {

std::string FlipDecisionName(FlipDecision decision) {
  switch (decision) {
    case FlipDecision::kSingle:
      return "single";
    case FlipDecision::kUnambiguous:
      return "unambiguous";
    case FlipDecision::kCoplanar:
      return "coplanar";
    case FlipDecision::kTemporal:
      return "temporal";
    case FlipDecision::kLowestError:
      return "lowest_error";
  }
  return "unknown";
}

bool ImageDecides(const TagPose& pose, const TagFlipResolverParams& params) {
  if (!pose.alternative) return false;
  const double gap_px2 = 4.0 * (pose.alternative->rms_px * pose.alternative->rms_px -
                                pose.best.rms_px * pose.best.rms_px);
  return pose.ambiguity_ratio <= params.max_ambiguity_ratio && gap_px2 >= params.min_error_gap_px2;
}

TagFlipResolver::TagFlipResolver(const TagFlipResolverParams& params) : params_(params) {
  if (!(params.max_ambiguity_ratio >= 0.0 && params.max_ambiguity_ratio <= 1.0)) {
    throw std::invalid_argument("apriltag.flip.max_ambiguity_ratio = " +
                                std::to_string(params.max_ambiguity_ratio) + " must be in [0, 1]");
  }
  if (!(params.min_error_gap_px2 >= 0.0) || !(params.coplanar_tolerance_deg >= 0.0) ||
      !(params.max_track_gap_s >= 0.0)) {
    throw std::invalid_argument(
        "apriltag.flip: min_error_gap_px2, coplanar_tolerance_deg and max_track_gap_s must be "
        ">= 0");
  }
}

bool TagFlipResolver::ChooseCoplanar(const TagPose& pose,
                                     const std::vector<Eigen::Vector3d>& references,
                                     FlipChoice* choice) const {
  if (references.empty() || params_.coplanar_tolerance_deg <= 0.0) return false;
  const double cos_tolerance = std::cos(params_.coplanar_tolerance_deg * M_PI / 180.0);
  auto fits = [&](const Eigen::Isometry3d& T_CT) {
    const Eigen::Vector3d normal_C = T_CT.linear().col(2);
    for (const Eigen::Vector3d& reference : references) {
      if (normal_C.dot(reference) >= cos_tolerance) return true;
    }
    return false;
  };
  const bool best_fits = fits(pose.best.T_CT);
  const bool alternative_fits = fits(pose.alternative->T_CT);
  if (best_fits == alternative_fits) return false;
  choice->use_alternative = alternative_fits;
  choice->decision = FlipDecision::kCoplanar;
  return true;
}

bool TagFlipResolver::UpdateTrack(double t_s, const TagPoseInImage& tag, bool* had_history) {
  // A single solution is decisive: the other hypothesis gets this many px^2 of penalty.
  constexpr double kSinglePenalty_px2 = 100.0;
  const TagPose& pose = tag.pose;
  const Eigen::Matrix3d& R_best = pose.best.T_CT.linear();
  const Eigen::Matrix3d& R_alternative =
      pose.alternative ? pose.alternative->T_CT.linear() : R_best;
  const double sse_best = 4.0 * pose.best.rms_px * pose.best.rms_px;
  const double sse_alternative = pose.alternative
                                     ? 4.0 * pose.alternative->rms_px * pose.alternative->rms_px
                                     : sse_best + kSinglePenalty_px2;
  const auto key = std::make_pair(tag.family, tag.id);
  auto it = tracks_.find(key);
  *had_history = it != tracks_.end() && t_s - it->second.t_s <= params_.max_track_gap_s;
  if (!*had_history) {
    tracks_[key] = Track{{R_best, R_alternative}, {sse_best, sse_alternative}, t_s};
    return sse_alternative < sse_best;
  }
  Track& track = it->second;
  auto angle = [](const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
    return control::LogSo3(a.transpose() * b).norm();
  };
  // best -> hypothesis 0 unless the crossed assignment is closer.
  const bool crossed = angle(R_best, track.R_CT[1]) + angle(R_alternative, track.R_CT[0]) <
                       angle(R_best, track.R_CT[0]) + angle(R_alternative, track.R_CT[1]);
  const int best_hypothesis = crossed ? 1 : 0;
  track.R_CT[best_hypothesis] = R_best;
  track.R_CT[1 - best_hypothesis] = R_alternative;
  track.cost[best_hypothesis] += sse_best;
  track.cost[1 - best_hypothesis] += sse_alternative;
  track.t_s = t_s;
  return track.cost[1 - best_hypothesis] < track.cost[best_hypothesis];
}

std::vector<FlipChoice> TagFlipResolver::Resolve(double t_s,
                                                 const std::vector<TagPoseInImage>& tags) {
  const std::size_t n = tags.size();
  std::vector<FlipChoice> choices(n);
  std::vector<bool> decided(n, false);
  // Every tag's track is updated first: the evidence of this frame counts for the temporal rule.
  std::vector<bool> temporal_alternative(n), has_history(n);
  for (std::size_t i = 0; i < n; ++i) {
    bool history = false;
    temporal_alternative[i] = UpdateTrack(t_s, tags[i], &history);
    has_history[i] = history;
  }
  auto chosen = [&](std::size_t i) -> const Eigen::Isometry3d& {
    return choices[i].use_alternative ? tags[i].pose.alternative->T_CT : tags[i].pose.best.T_CT;
  };
  // Rule 1: what the image decides.
  std::vector<Eigen::Vector3d> image_normals;
  for (std::size_t i = 0; i < n; ++i) {
    const TagPose& pose = tags[i].pose;
    if (!pose.alternative) {
      choices[i].decision = FlipDecision::kSingle;
    } else if (!params_.enabled || ImageDecides(pose, params_)) {
      choices[i].decision =
          params_.enabled ? FlipDecision::kUnambiguous : FlipDecision::kLowestError;
    } else {
      continue;
    }
    decided[i] = true;
    image_normals.push_back(pose.best.T_CT.linear().col(2));
  }
  // Rules 2 and 3: coplanar with the image's decisions, else the tag's own history.
  std::vector<Eigen::Vector3d> temporal_normals;
  for (std::size_t i = 0; i < n; ++i) {
    if (decided[i]) continue;
    if (ChooseCoplanar(tags[i].pose, image_normals, &choices[i])) {
      decided[i] = true;
    } else if (has_history[i]) {
      choices[i] = {temporal_alternative[i], FlipDecision::kTemporal};
      decided[i] = true;
      temporal_normals.push_back(chosen(i).linear().col(2));
    }
  }
  // Rules 4 and 5.
  for (std::size_t i = 0; i < n; ++i) {
    if (decided[i]) continue;
    if (!ChooseCoplanar(tags[i].pose, temporal_normals, &choices[i])) {
      choices[i] = {false, FlipDecision::kLowestError};
    }
  }
  return choices;
}

}  // namespace aperture::perception
