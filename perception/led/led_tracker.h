#pragma once
// Monocular pose tracking of an infrared-LED target (Faessler thesis, Appendix C, Fig. C.3):
// detection (C.1)-(C.4) -> prediction (C.6), (C.7) with nearest-detection matching and
// verification (C.3.5) -> brute-force correspondence search (Algorithm 1) only when that fails ->
// Gauss-Newton refinement with covariance (C.8), (C.9).
// Beyond the thesis (issue 22): while tracking, when fewer than four predicted LEDs find a
// detection of their own (the body hides LEDs, or LEDs share a blob: merged, or a hidden LED
// predicted onto a visible one's blob), the pose comes from three or more detections through P3P
// candidates near the prediction (led_pose_near_prediction.h), refined, and kept only when its
// covariance bounds the rotation within max_near_prediction_rotation_sigma_deg. A fresh start
// still needs four LEDs (Algorithm 1), and (issue 21) a margin between its best labelling and the
// runner-up (labelling_margin_ratio), else it reports the frame ambiguous.
//
// Output: T_CT (p_C = T_CT * p_T) with its 6x6 covariance [p_CT; rotation in C], or no pose with
// the reason. A blob serving several LEDs (e.g. two LEDs merged) is never used; frames left with
// too few unique correspondences (< 4 on a fresh start, < 3 near the prediction) or whose refined
// reprojection error exceeds max_rms_px are rejected rather than answered with a confident wrong
// pose.
// Not thread-safe (keeps the pose history and buffers); one tracker per camera.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <deque>
#include <limits>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "perception/camera/camera_model.h"
#include "perception/led/led_configuration.h"
#include "perception/led/led_correspondence_search.h"
#include "perception/led/led_detector.h"
#include "perception/led/led_pose_near_prediction.h"
#include "perception/led/led_pose_refiner.h"

namespace aperture::perception {

struct LedTrackerParams {
  LedDetectorParams detector;
  LedCorrespondenceParams correspondence;
  LedPoseRefinerParams refiner;
  double prediction_match_px = 5.0;  // prediction -> nearest detection gate (thesis: 5 px)
  int roi_half_size_px = 24;         // ROI around each predicted LED; blob radius + motion
  double max_rms_px = 2.0;           // refined reprojection RMS above: inconsistent frame
  // Pose from fewer than 4 matched LEDs while tracking.
  LedNearPredictionParams near_prediction;
  // Largest rotation standard deviation (C.9 at detection_sigma_px) a pose near the prediction
  // may have [deg]: beyond it the LEDs barely fix the rotation and the prediction, not the
  // image, would pick the pose. At 1 px, `bench led` body_occlusion's three-LED poses at
  // 1.8-2.5 m have 6.6-9.3 deg and its four-LED poses up to 27 deg (sigma grows with distance),
  // so 30 deg rejects only a geometry worse than any the four-LED path meets there.
  double max_near_prediction_rotation_sigma_deg = 30.0;
  // Margin between the best and the second-best labelling of a fresh start (issue 21): the
  // brute-force pose (Algorithm 1, C.3.4) is accepted only when the runner-up labelling, refined
  // like the best (C.8), has a reprojection RMS at least this many times the best's; else the
  // frame is ambiguous. The thesis has no such test and saw wrong labellings > 90 deg off beyond
  // 5 m (Fig. C.7); with a compact target at 4-5 m a relabelling fits within lambda_r = 5 px.
  // 0 turns the test off. See max_rms_px for the absolute bound.
  double labelling_margin_ratio = 2.0;
  // Table C.2's timing protocol: every frame is detected on the full image and labelled by brute
  // force (Algorithm 1), the thesis' "enforced brute-force correspondence search in each step".
  // The prediction (C.6), (C.7) is still computed (and timed) from the kept history of poses,
  // but not used. For benchmarks; a tracker should leave it off.
  bool force_brute_force = false;
};

enum class LedTrackStatus {
  kTracked,             // prediction verified, refined
  kReinitialized,       // brute-force correspondences, refined
  kNoDetections,        // fewer than 3 blobs (also: nothing in the image)
  kNoCorrespondences,   // brute force found < 4 LEDs or no pose candidate fits
  kAmbiguous,           // blobs shared by several LEDs leave too few unique correspondences,
                        // or (fresh start) a second labelling fits nearly as well as the best
                        // (labelling_margin_ratio)
  kInconsistent,        // refinement failed, reprojection RMS > max_rms_px, or (near the
                        // prediction) rotation sigma > max_near_prediction_rotation_sigma_deg
  // < 4 predicted LEDs matched: P3P candidate near the prediction, refined (issue 22).
  kTrackedNearPrediction,
};
std::string LedTrackStatusName(LedTrackStatus status);

// Wall-clock time each stage of one Track call took [s]; 0 when the stage did not run (Table
// C.2's steps). For benchmarks: the figures depend on the machine and its load.
struct LedStageTimes {
  double detection_s = 0.0;    // ROI and, when tracking was lost, full-image detection
  double prediction_s = 0.0;   // (C.6), (C.7), nearest-detection matching and verification
  double brute_force_s = 0.0;  // Algorithm 1
  double refinement_s = 0.0;   // Gauss-Newton and covariance (C.8), (C.9)
  // P3P candidates near the prediction (< 4 LEDs matched).
  double near_prediction_s = 0.0;
};

struct LedTrackResult {
  LedTrackStatus status = LedTrackStatus::kNoDetections;
  std::optional<Eigen::Isometry3d> T_CT;
  std::optional<Matrix6d> covariance;  // with T_CT
  std::vector<LedDetection> detections;
  std::vector<LedCorrespondence> correspondences;  // used for the pose (unique detections)
  int merged_detections = 0;  // detections that several LEDs claimed (dropped)
  double rms_px = 0.0;
  // Brute force: the refined reprojection RMS of the second-best labelling [px]; infinite when
  // there is none (or its refinement failed).
  double runner_up_rms_px = std::numeric_limits<double>::infinity();
  bool used_roi = false;      // detection ran on ROIs around the prediction
  bool used_brute_force = false;
  // The P3P search near the prediction ran.
  bool used_near_prediction = false;
  std::string warning;        // e.g. the detector's blob cap
  LedStageTimes stage_times;
  bool has_pose() const { return T_CT.has_value(); }
};

class LedTracker {
 public:
  LedTracker(LedConfiguration configuration, std::shared_ptr<const CameraModel> camera,
             const LedTrackerParams& params = {});

  // One frame at time t_s (seconds, increasing). image: 8-bit gray or BGR of the camera's size.
  LedTrackResult Track(const cv::Mat& image, double t_s);
  // The pose predicted for t_s by (C.6), (C.7); none without a previous pose.
  std::optional<Eigen::Isometry3d> Predict(double t_s) const;
  void Reset() { history_.clear(); }

  const LedConfiguration& configuration() const { return configuration_; }
  const CameraModel& camera() const { return *camera_; }

 private:
  struct TimedPose {
    double t_s;
    Eigen::Isometry3d T_CT;
  };
  // Nearest detection within prediction_match_px of every predicted LED.
  std::vector<LedCorrespondence> MatchPrediction(const Eigen::Isometry3d& T_CT_predicted,
                                                 const std::vector<LedDetection>& detections) const;
  // Pose from fewer than 4 matched LEDs near the prediction; false when none passes.
  bool TrackNearPrediction(LedTrackResult* result, const Eigen::Isometry3d& T_CT_predicted,
                           double t_s);
  // The correspondences whose detection no other LED claims (*unique) with their LEDs' p_T and
  // detections' px appended; returns the number of detections several LEDs claim.
  int UniquePairs(const std::vector<LedCorrespondence>& correspondences,
                  const std::vector<LedDetection>& detections,
                  std::vector<LedCorrespondence>* unique, std::vector<Eigen::Vector3d>* p_T,
                  std::vector<Eigen::Vector2d>* px) const;
  // Reprojection RMS [px] of correspondences (those with unique detections, >= 4) refined from
  // T_CT_initial (C.8); infinite when fewer or when the refinement fails.
  double RefinedRms(const std::vector<LedCorrespondence>& correspondences,
                    const std::vector<LedDetection>& detections,
                    const Eigen::Isometry3d& T_CT_initial) const;
  // Refines T_CT_initial on the correspondences with unique detections (at least
  // min_correspondences of them) and records the pose when the refinement's rotation sigma is
  // at most max_rotation_sigma_rad; else sets the failure status and forgets the track.
  void Finish(LedTrackResult* result, const std::vector<LedCorrespondence>& correspondences,
              const Eigen::Isometry3d& T_CT_initial, double t_s, int min_correspondences = 4,
              double max_rotation_sigma_rad = std::numeric_limits<double>::infinity());

  LedConfiguration configuration_;
  std::shared_ptr<const CameraModel> camera_;
  LedTrackerParams params_;
  LedDetector detector_;
  LedCorrespondenceSearch search_;
  std::deque<TimedPose> history_;  // last two estimated poses
};

}  // namespace aperture::perception
