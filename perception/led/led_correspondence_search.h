#pragma once
// Correspondences between LED detections D and the LEDs L of a target (Faessler thesis C.3.4,
// C.3.5).
//  - FindByBruteForce: Algorithm 1. P3P on every combination of 3 detections x permutation of 3
//    LEDs (N of (C.5) candidates); every LED not used whose reprojection lies within lambda_r of
//    a detection votes for that (LED, detection) bin, and for the three pairs that made the
//    candidate. Correspondences are then taken greedily from the highest bin, each LED once,
//    while the bin holds >= acceptance_ratio * C(n_L, 3) votes (Fig. C.5). One detection may
//    serve several LEDs (merged blobs; the tracker decides), one LED never several detections.
//    Deviations, needed because with a compact target and lambda_r = 5 px wrong labellings often
//    reproject some remaining LED near a detection by chance and swamp the true bins: a remaining
//    LED does not vote for one of the candidate's own three detections, and only the candidates
//    that explain the most remaining LEDs of the frame and share the labelling (all LED-detection
//    pairs they imply) reproduced by the most candidates (>= 2; ties: smallest reprojection
//    error) vote: the true labelling of m LEDs comes out of all C(m, 3) of its 3-subsets, a
//    chance one out of one. The true bins then hold C(m, 3) votes, m the number of LEDs those
//    candidates explain (n_L with every LED visible, n_L - 1 with one occluded), so the acceptance is acceptance_ratio * C(m, 3) (the thesis'
//    0.5 C(n_L, 3) when all are visible; a fresh start with 4 of 5 LEDs still finds the pose).
//    The accepted correspondences must then agree with the consensus pose (the P3P candidate of
//    the accepted set with the most reprojections within lambda_r); the others are dropped. An
//    LED still unmatched gets the nearest detection within lambda_r of its reprojection from that
//    pose, even a taken one (merged blobs).
//  - Verify: the check of predicted correspondences: for every 3-subset, P3P, reproject the other
//    corresponded LEDs; the subset passes when for one candidate >= min_inlier_ratio of them lie
//    within lambda_r; the set passes when > min_subset_ratio of the subsets pass.
//    FindByBruteForce also returns the runner-up: among the other labellings that explain as many
//    LEDs (each one reproduced by any number of candidates), the one with the smallest mean
//    squared reprojection error of the LEDs it explains, with its best candidate pose. The tracker
//    compares the two after refinement (LedTrackerParams::labelling_margin_ratio): at 4-5 m a
//    wrong labelling of a compact target can fit within lambda_r nearly as well as the true one
//    (Fig. C.7's outliers).
// Both also return the candidate pose with the most correspondences within lambda_r, ties broken
// by their squared reprojection error (the Gauss-Newton start, C.3.6).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "perception/camera/camera_model.h"
#include "perception/led/led_detector.h"
#include "perception/led/p3p_solver.h"

namespace aperture::perception {

struct LedCorrespondenceParams {
  P3pMethod p3p_method = P3pMethod::kKneip;
  double reprojection_threshold_px = 5.0;  // lambda_r; thesis: 5 px
  double acceptance_ratio = 0.5;           // of C(m, 3) votes, m LEDs explained (Fig. C.5)
  double min_inlier_ratio = 0.75;          // verification: reprojections within lambda_r
  double min_subset_ratio = 0.7;           // verification: 3-subsets that must pass
};

struct LedCorrespondence {
  int led = -1;        // index into the configuration
  int detection = -1;  // index into the detections
};

struct LedCorrespondenceResult {
  std::vector<LedCorrespondence> correspondences;  // sorted by LED
  std::optional<Eigen::Isometry3d> T_CT;  // best candidate pose; none when no candidate fits
  // FindByBruteForce: the second-best labelling (sorted by LED; empty when there is none) and its
  // best P3P candidate.
  std::vector<LedCorrespondence> runner_up_correspondences;
  std::optional<Eigen::Isometry3d> runner_up_T_CT;
  int pose_candidates = 0;                // P3P solutions evaluated
  double verified_ratio = 0.0;            // Verify: fraction of 3-subsets that passed
  bool verified = false;                  // Verify: the rule above held
};

class LedCorrespondenceSearch {
 public:
  // FindByBruteForce labels detections in 8 bits (and costs O(n_D^3) P3P calls).
  static constexpr int kMaxDetections = 254;

  LedCorrespondenceSearch(const std::vector<Eigen::Vector3d>& p_T,
                          const LedCorrespondenceParams& params = {});

  // Algorithm 1. histogram (optional) receives the votes, rows = LEDs, columns = detections.
  // Throws std::invalid_argument for more than kMaxDetections detections.
  LedCorrespondenceResult FindByBruteForce(const std::vector<LedDetection>& detections,
                                           const CameraModel& camera,
                                           Eigen::MatrixXi* histogram = nullptr) const;

  // Verification of given correspondences (C.3.5); needs >= 4 with distinct detections.
  LedCorrespondenceResult Verify(const std::vector<LedCorrespondence>& correspondences,
                                 const std::vector<LedDetection>& detections,
                                 const CameraModel& camera) const;

  const LedCorrespondenceParams& params() const { return params_; }

 private:
  // Best-fitting P3P candidate over all 3-subsets of correspondences with distinct detections.
  std::optional<Eigen::Isometry3d> BestCandidate(
      const std::vector<LedCorrespondence>& correspondences,
      const std::vector<LedDetection>& detections, const CameraModel& camera) const;

  std::vector<Eigen::Vector3d> p_T_;
  LedCorrespondenceParams params_;
};

}  // namespace aperture::perception
