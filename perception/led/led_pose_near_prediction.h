#pragma once
// A pose of the LED target from as few as three detections, while tracking (issue 22 item 3; an
// extension of Faessler thesis C.3.5, where the tracker needs four LEDs): when the body hides LEDs
// and fewer than four predicted LEDs find a detection, P3P on every 3-subset of the detections x
// every ordered triple of LEDs gives up to four candidate poses each (C.5 counts them), and the
// prediction (C.6), (C.7) chooses among them:
//  - gate: a candidate is kept only when no LED's image moves by more than gate_px between the
//    candidate and the predicted pose (LedImageDistance); the thesis accepts a prediction whose
//    LEDs lie within 5 px of their detections, so the same 5 px bound the motion a frame may add.
//    A wrong assignment puts an LED's image on another LED's detection, one LED spacing (> 10 px at
//    the bench's 2.5 m) away from its prediction, and P3P's mirror solutions turn the target by
//    tens of degrees: both fail the gate.
//  - reprojection of every LED: each LED projecting into the image at the candidate takes the
//    nearest detection within lambda_r (LedCorrespondenceParams::reprojection_threshold_px);
//    LEDs without one count as hidden. The candidate explaining the most LEDs wins, then the one
//    nearest the prediction.
//  - uniqueness: a candidate with another labelling that explains as many LEDs inside the gate
//    (two LEDs' images within the gate of each other, e.g. merging) makes the frame ambiguous.
// The caller refines the returned correspondences (C.8) and checks the covariance (C.9): three
// LEDs fix the pose exactly, so the reprojection error cannot reject a wrong one; the covariance
// shows when they fix it badly (nearly collinear images).
// A fresh start (no prediction) must not use this: without the gate three points do not choose.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "perception/camera/camera_model.h"
#include "perception/led/led_correspondence_search.h"
#include "perception/led/led_detector.h"

namespace aperture::perception {

struct LedNearPredictionParams {
  // Largest displacement of any LED's image between a candidate pose and the prediction [px].
  // 5 px: the thesis' prediction gate (C.3.5), which the four-LED tracking path also uses.
  double gate_px = 5.0;
};

enum class LedNearPredictionStatus {
  kFound,
  kTooFewDetections,   // fewer than 3 detections
  kNoCandidateInGate,  // no P3P candidate within gate_px of the prediction
  kAmbiguous,          // two labellings explain the frame equally well inside the gate
};
std::string LedNearPredictionStatusName(LedNearPredictionStatus status);

struct LedNearPredictionResult {
  LedNearPredictionStatus status = LedNearPredictionStatus::kTooFewDetections;
  std::optional<Eigen::Isometry3d> T_CT;  // the chosen P3P candidate (before refinement)
  // Every LED with a detection within lambda_r at T_CT (>= 3), sorted by LED; one detection may
  // serve several LEDs (merged blobs: the tracker drops those).
  std::vector<LedCorrespondence> correspondences;
  double distance_px = 0.0;  // LedImageDistance of T_CT from the prediction
  int pose_candidates = 0;   // P3P solutions evaluated
  int candidates_in_gate = 0;
};

// Largest distance [px] between the images of the same LED under T_CT_a and T_CT_b, over the LEDs
// p_T; +inf when an LED projects under one pose and not the other (or under neither).
double LedImageDistance(const CameraModel& camera, const std::vector<Eigen::Vector3d>& p_T,
                        const Eigen::Isometry3d& T_CT_a, const Eigen::Isometry3d& T_CT_b);

// The pose candidate near T_CT_predicted explaining the most detections (see above). p_T: the
// configuration's LEDs [m, frame T]; detections: e.g. those in the ROIs around the prediction.
LedNearPredictionResult FindLedPoseNearPrediction(const std::vector<Eigen::Vector3d>& p_T,
                                                  const std::vector<LedDetection>& detections,
                                                  const CameraModel& camera,
                                                  const Eigen::Isometry3d& T_CT_predicted,
                                                  const LedCorrespondenceParams& correspondence,
                                                  const LedNearPredictionParams& params = {});

}  // namespace aperture::perception
