#include "perception/led/led_tracker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

#include "control/so3.h"
#include "perception/elapsed_time.h"

namespace aperture::perception {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

std::string LedTrackStatusName(LedTrackStatus status) {
  switch (status) {
    case LedTrackStatus::kTracked:
      return "tracked";
    case LedTrackStatus::kReinitialized:
      return "reinitialized";
    case LedTrackStatus::kNoDetections:
      return "no_detections";
    case LedTrackStatus::kNoCorrespondences:
      return "no_correspondences";
    case LedTrackStatus::kAmbiguous:
      return "ambiguous";
    case LedTrackStatus::kInconsistent:
      return "inconsistent";
    case LedTrackStatus::kTrackedNearPrediction:
      return "tracked_near_prediction";
  }
  return "unknown";
}

LedTracker::LedTracker(LedConfiguration configuration, std::shared_ptr<const CameraModel> camera,
                       const LedTrackerParams& params)
    : configuration_(std::move(configuration)),
      camera_(std::move(camera)),
      params_(params),
      detector_(params.detector),
      search_(configuration_.p_T(), params.correspondence) {
  if (!camera_) throw std::invalid_argument("LedTracker: no camera model given");
}

std::optional<Eigen::Isometry3d> LedTracker::Predict(double t_s) const {
  if (history_.empty()) return std::nullopt;
  const TimedPose& last = history_.back();
  if (history_.size() == 1) return last.T_CT;  // (C.7): Delta T = 0 for n_P = 1
  const TimedPose& previous = history_.front();
  const double dt_previous = last.t_s - previous.t_s;
  const double delta = dt_previous > 0.0 ? (t_s - last.t_s) / dt_previous : 0.0;  // (C.7)
  const control::Vector6d xi_last = control::LogSe3(last.T_CT);
  return control::ExpSe3(xi_last + delta * (xi_last - control::LogSe3(previous.T_CT)));  // (C.6)
}

std::vector<LedCorrespondence> LedTracker::MatchPrediction(
    const Eigen::Isometry3d& T_CT_predicted, const std::vector<LedDetection>& detections) const {
  std::vector<LedCorrespondence> matches;
  const double gate_sq = params_.prediction_match_px * params_.prediction_match_px;
  for (int led = 0; led < configuration_.size(); ++led) {
    Eigen::Vector2d px;
    if (!camera_->Project(T_CT_predicted * configuration_.p_T()[led], &px)) continue;
    int nearest = -1;
    double nearest_sq = gate_sq;
    for (int d = 0; d < static_cast<int>(detections.size()); ++d) {
      const double distance_sq = (detections[d].px - px).squaredNorm();
      if (distance_sq < nearest_sq) {
        nearest_sq = distance_sq;
        nearest = d;
      }
    }
    if (nearest >= 0) matches.push_back({led, nearest});
  }
  return matches;
}

LedTrackResult LedTracker::Track(const cv::Mat& image, double t_s) {
  LedTrackResult result;
  LedStageTimes& times = result.stage_times;
  Clock::time_point start = Clock::now();
  const std::optional<Eigen::Isometry3d> prediction = Predict(t_s);
  times.prediction_s = SecondsSince(start);
  if (prediction && !params_.force_brute_force) {
    std::vector<cv::Rect> rois;
    for (const Eigen::Vector3d& p_T : configuration_.p_T()) {
      Eigen::Vector2d px;
      if (!camera_->Project(*prediction * p_T, &px) || !camera_->IsInImage(px)) continue;
      const int r = params_.roi_half_size_px;
      rois.emplace_back(static_cast<int>(px.x()) - r, static_cast<int>(px.y()) - r, 2 * r + 1,
                        2 * r + 1);
    }
    if (!rois.empty()) {
      start = Clock::now();
      LedDetectionResult detected = detector_.Detect(image, *camera_, rois);
      times.detection_s = SecondsSince(start);
      start = Clock::now();
      result.detections = std::move(detected.detections);
      result.warning = detected.warning;
      result.used_roi = true;
      const std::vector<LedCorrespondence> matches =
          MatchPrediction(*prediction, result.detections);
      std::vector<LedCorrespondence> unique;
      for (const LedCorrespondence& match : matches) {
        const auto claims = std::count_if(matches.begin(), matches.end(), [&](const auto& other) {
          return other.detection == match.detection;
        });
        if (claims == 1) unique.push_back(match);
      }
      // Predicted LEDs converging on shared blobs (merging, Section C.4.2, or a hidden LED
      // predicted onto a visible one's blob) leave fewer than four unique correspondences.
      const bool shared_blobs = unique.size() < matches.size() && unique.size() < 4;
      if (!shared_blobs) {
        const LedCorrespondenceResult verified =
            search_.Verify(unique, result.detections, *camera_);
        if (verified.verified) {
          times.prediction_s += SecondsSince(start);
          result.status = LedTrackStatus::kTracked;
          Finish(&result, matches, *prediction, t_s);
          return result;
        }
      }
      times.prediction_s += SecondsSince(start);
      if (unique.size() < 4 && TrackNearPrediction(&result, *prediction, t_s)) return result;
      if (shared_blobs) {
        result.status = LedTrackStatus::kAmbiguous;
        result.correspondences = matches;
        result.merged_detections = static_cast<int>(matches.size() - unique.size());
        history_.clear();
        return result;
      }
    }
  }
  // Lost (or never found): full image and brute force.
  start = Clock::now();
  LedDetectionResult detected = detector_.Detect(image, *camera_);
  times.detection_s += SecondsSince(start);
  result.detections = std::move(detected.detections);
  result.warning = detected.warning;
  result.used_roi = false;
  result.correspondences.clear();  // of a failed attempt near the prediction
  result.merged_detections = 0;
  if (!params_.force_brute_force) history_.clear();
  if (result.detections.size() < 3) {
    result.status = LedTrackStatus::kNoDetections;
    return result;
  }
  result.used_brute_force = true;
  start = Clock::now();
  const LedCorrespondenceResult found = search_.FindByBruteForce(result.detections, *camera_);
  times.brute_force_s = SecondsSince(start);
  if (found.correspondences.size() < 4 || !found.T_CT) {
    result.status = LedTrackStatus::kNoCorrespondences;
    result.correspondences = found.correspondences;
    return result;
  }
  result.status = LedTrackStatus::kReinitialized;
  Finish(&result, found.correspondences, *found.T_CT, t_s);
  if (result.has_pose() && found.runner_up_T_CT) {
    start = Clock::now();
    result.runner_up_rms_px = RefinedRms(found.runner_up_correspondences, result.detections,
                                         *found.runner_up_T_CT);
    result.stage_times.refinement_s += SecondsSince(start);
    if (result.runner_up_rms_px < params_.labelling_margin_ratio * result.rms_px) {
      result.status = LedTrackStatus::kAmbiguous;
      result.T_CT.reset();
      result.covariance.reset();
      history_.clear();
    }
  }
  return result;
}

int LedTracker::UniquePairs(const std::vector<LedCorrespondence>& correspondences,
                            const std::vector<LedDetection>& detections,
                            std::vector<LedCorrespondence>* unique,
                            std::vector<Eigen::Vector3d>* p_T,
                            std::vector<Eigen::Vector2d>* px) const {
  std::map<int, int> claims;
  for (const LedCorrespondence& c : correspondences) ++claims[c.detection];
  unique->clear();
  for (const LedCorrespondence& c : correspondences) {
    if (claims[c.detection] > 1) continue;
    unique->push_back(c);
    p_T->push_back(configuration_.p_T()[c.led]);
    px->push_back(detections[c.detection].px);
  }
  int shared = 0;
  for (const auto& [detection, count] : claims) shared += count > 1 ? 1 : 0;
  return shared;
}

double LedTracker::RefinedRms(const std::vector<LedCorrespondence>& correspondences,
                              const std::vector<LedDetection>& detections,
                              const Eigen::Isometry3d& T_CT_initial) const {
  std::vector<LedCorrespondence> unique;
  std::vector<Eigen::Vector3d> p_T;
  std::vector<Eigen::Vector2d> px;
  UniquePairs(correspondences, detections, &unique, &p_T, &px);
  if (p_T.size() < 4) return std::numeric_limits<double>::infinity();
  const LedPoseRefinement refined = RefineLedPose(*camera_, p_T, px, T_CT_initial, params_.refiner);
  return refined.valid ? refined.rms_px : std::numeric_limits<double>::infinity();
}

bool LedTracker::TrackNearPrediction(LedTrackResult* result,
                                     const Eigen::Isometry3d& T_CT_predicted, double t_s) {
  result->used_near_prediction = true;
  const Clock::time_point start = Clock::now();
  const LedNearPredictionResult found =
      FindLedPoseNearPrediction(configuration_.p_T(), result->detections, *camera_, T_CT_predicted,
                                params_.correspondence, params_.near_prediction);
  result->stage_times.near_prediction_s = SecondsSince(start);
  if (found.status != LedNearPredictionStatus::kFound) return false;
  result->status = LedTrackStatus::kTrackedNearPrediction;
  Finish(result, found.correspondences, *found.T_CT, t_s, /*min_correspondences=*/3,
         params_.max_near_prediction_rotation_sigma_deg * M_PI / 180.0);
  return result->has_pose();
}

void LedTracker::Finish(LedTrackResult* result,
                        const std::vector<LedCorrespondence>& correspondences,
                        const Eigen::Isometry3d& T_CT_initial, double t_s, int min_correspondences,
                        double max_rotation_sigma_rad) {
  // A blob claimed by several LEDs (merged LEDs, Section C.4.2) has a centroid between them:
  // drop it instead of pulling the pose towards it.
  std::vector<Eigen::Vector3d> p_T;
  std::vector<Eigen::Vector2d> px;
  result->merged_detections += UniquePairs(correspondences, result->detections,
                                           &result->correspondences, &p_T, &px);
  if (static_cast<int>(p_T.size()) < min_correspondences) {
    result->status = LedTrackStatus::kAmbiguous;
    history_.clear();
    return;
  }
  const Clock::time_point start = Clock::now();
  const LedPoseRefinement refined = RefineLedPose(*camera_, p_T, px, T_CT_initial, params_.refiner);
  result->stage_times.refinement_s = SecondsSince(start);
  result->rms_px = refined.rms_px;
  if (!refined.valid || refined.rms_px > params_.max_rms_px ||
      !(LargestStandardDeviation(refined.covariance.bottomRightCorner<3, 3>()) <=
        max_rotation_sigma_rad)) {
    result->status = LedTrackStatus::kInconsistent;
    history_.clear();
    return;
  }
  result->T_CT = refined.T_CT;
  result->covariance = refined.covariance;
  history_.push_back({t_s, refined.T_CT});
  while (history_.size() > 2) history_.pop_front();
}

}  // namespace aperture::perception
