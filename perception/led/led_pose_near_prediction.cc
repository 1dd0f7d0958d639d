#include "perception/led/led_pose_near_prediction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "perception/led/p3p_solver.h"

namespace aperture::perception {
namespace {

// A P3P candidate inside the gate: the detection each LED takes at it (-1: none, hidden).
struct Candidate {
  Eigen::Isometry3d T_CT;
  double distance_px;
  std::vector<int> detection_of_led;
  int explained;
};

std::vector<int> NearestDetections(const CameraModel& camera,
                                   const std::vector<Eigen::Vector3d>& p_T,
                                   const std::vector<LedDetection>& detections,
                                   const Eigen::Isometry3d& T_CT, double threshold_px) {
  std::vector<int> detection_of_led(p_T.size(), -1);
  for (std::size_t led = 0; led < p_T.size(); ++led) {
    Eigen::Vector2d px;
    if (!camera.Project(T_CT * p_T[led], &px) || !camera.IsInImage(px)) continue;
    double nearest_sq = threshold_px * threshold_px;
    for (std::size_t d = 0; d < detections.size(); ++d) {
      const double distance_sq = (detections[d].px - px).squaredNorm();
      if (distance_sq < nearest_sq) {
        nearest_sq = distance_sq;
        detection_of_led[led] = static_cast<int>(d);
      }
    }
  }
  return detection_of_led;
}

}  // namespace

std::string LedNearPredictionStatusName(LedNearPredictionStatus status) {
  switch (status) {
    case LedNearPredictionStatus::kFound:
      return "found";
    case LedNearPredictionStatus::kTooFewDetections:
      return "too_few_detections";
    case LedNearPredictionStatus::kNoCandidateInGate:
      return "no_candidate_in_gate";
    case LedNearPredictionStatus::kAmbiguous:
      return "ambiguous";
  }
  return "unknown";
}

double LedImageDistance(const CameraModel& camera, const std::vector<Eigen::Vector3d>& p_T,
                        const Eigen::Isometry3d& T_CT_a, const Eigen::Isometry3d& T_CT_b) {
  double largest = 0.0;
  for (const Eigen::Vector3d& p : p_T) {
    Eigen::Vector2d px_a, px_b;
    if (!camera.Project(T_CT_a * p, &px_a) || !camera.Project(T_CT_b * p, &px_b)) {
      return std::numeric_limits<double>::infinity();
    }
    largest = std::max(largest, (px_a - px_b).norm());
  }
  return largest;
}

LedNearPredictionResult FindLedPoseNearPrediction(const std::vector<Eigen::Vector3d>& p_T,
                                                  const std::vector<LedDetection>& detections,
                                                  const CameraModel& camera,
                                                  const Eigen::Isometry3d& T_CT_predicted,
                                                  const LedCorrespondenceParams& correspondence,
                                                  const LedNearPredictionParams& params) {
  LedNearPredictionResult result;
  const int n_leds = static_cast<int>(p_T.size());
  const int n_detections = static_cast<int>(detections.size());
  if (n_detections < 3) return result;
  std::vector<Candidate> in_gate;
  std::vector<Eigen::Isometry3d> solutions;
  std::array<Eigen::Vector3d, 3> f_C, p_T3;
  for (int a = 0; a < n_detections; ++a) {
    for (int b = a + 1; b < n_detections; ++b) {
      for (int c = b + 1; c < n_detections; ++c) {
        f_C = {detections[a].f_C, detections[b].f_C, detections[c].f_C};
        for (int i = 0; i < n_leds; ++i) {
          for (int j = 0; j < n_leds; ++j) {
            if (j == i) continue;
            for (int l = 0; l < n_leds; ++l) {
              if (l == i || l == j) continue;
              p_T3 = {p_T[i], p_T[j], p_T[l]};
              SolveP3p(correspondence.p3p_method, f_C, p_T3, &solutions);
              result.pose_candidates += static_cast<int>(solutions.size());
              for (const Eigen::Isometry3d& T_CT : solutions) {
                const double distance_px = LedImageDistance(camera, p_T, T_CT, T_CT_predicted);
                if (!(distance_px <= params.gate_px)) continue;
                std::vector<int> detection_of_led = NearestDetections(
                    camera, p_T, detections, T_CT, correspondence.reprojection_threshold_px);
                const int explained =
                    static_cast<int>(std::count_if(detection_of_led.begin(), detection_of_led.end(),
                                                   [](int d) { return d >= 0; }));
                in_gate.push_back({T_CT, distance_px, std::move(detection_of_led), explained});
              }
            }
          }
        }
      }
    }
  }
  result.candidates_in_gate = static_cast<int>(in_gate.size());
  if (in_gate.empty()) {
    result.status = LedNearPredictionStatus::kNoCandidateInGate;
    return result;
  }
  const auto best =
      std::min_element(in_gate.begin(), in_gate.end(), [](const Candidate& x, const Candidate& y) {
        return x.explained != y.explained ? x.explained > y.explained
                                          : x.distance_px < y.distance_px;
      });
  for (const Candidate& other : in_gate) {
    if (other.explained == best->explained && other.detection_of_led != best->detection_of_led) {
      result.status = LedNearPredictionStatus::kAmbiguous;
      return result;
    }
  }
  result.status = LedNearPredictionStatus::kFound;
  result.T_CT = best->T_CT;
  result.distance_px = best->distance_px;
  for (int led = 0; led < n_leds; ++led) {
    if (best->detection_of_led[led] >= 0) {
      result.correspondences.push_back({led, best->detection_of_led[led]});
    }
  }
  return result;
}

}  // namespace aperture::perception
