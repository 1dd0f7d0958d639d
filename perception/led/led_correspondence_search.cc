#include "perception/led/led_correspondence_search.h"

#include <algorithm>
#include <array>
#include <limits>

namespace aperture::perception {
namespace {

int Choose3(int n) { return n * (n - 1) * (n - 2) / 6; }

}  // namespace

LedCorrespondenceSearch::LedCorrespondenceSearch(const std::vector<Eigen::Vector3d>& p_T,
                                                 const LedCorrespondenceParams& params)
    : p_T_(p_T), params_(params) {}

LedCorrespondenceResult LedCorrespondenceSearch::FindByBruteForce(
    const std::vector<LedDetection>& detections, const CameraModel& camera,
    Eigen::MatrixXi* histogram) const {
  const int n_leds = static_cast<int>(p_T_.size());
  const int n_detections = static_cast<int>(detections.size());
  Eigen::MatrixXi votes = Eigen::MatrixXi::Zero(n_leds, n_detections);
  LedCorrespondenceResult result;
  const double threshold_sq = params_.reprojection_threshold_px * params_.reprojection_threshold_px;
  std::vector<Eigen::Isometry3d> candidates;
  candidates.reserve(4);
  std::array<Eigen::Vector3d, 3> f_C, p_T;
  // Every candidate that explains at least one remaining LED, with its votes (Algorithm 1).
  struct Vote {
    int led, detection;
  };
  struct Candidate {
    std::array<int, 3> d3, l3;
    int matched_leds;  // remaining LEDs with a detection within lambda_r
    std::size_t first_vote, end_vote;
  };
  std::vector<Candidate> consistent;
  std::vector<Vote> remaining_votes;
  int max_matched = 0;
  for (int a = 0; a < n_detections; ++a) {
    for (int b = a + 1; b < n_detections; ++b) {
      for (int c = b + 1; c < n_detections; ++c) {
        const std::array<int, 3> d3{a, b, c};
        for (int k = 0; k < 3; ++k) f_C[k] = detections[d3[k]].f_C;
        for (int i = 0; i < n_leds; ++i) {
          for (int j = 0; j < n_leds; ++j) {
            if (j == i) continue;
            for (int l = 0; l < n_leds; ++l) {
              if (l == i || l == j) continue;
              p_T = {p_T_[i], p_T_[j], p_T_[l]};
              SolveP3p(params_.p3p_method, f_C, p_T, &candidates);
              result.pose_candidates += static_cast<int>(candidates.size());
              for (const Eigen::Isometry3d& T_CT : candidates) {
                const std::size_t first_vote = remaining_votes.size();
                int matched = 0;
                for (int r = 0; r < n_leds; ++r) {
                  if (r == i || r == j || r == l) continue;
                  Eigen::Vector2d px;
                  if (!camera.Project(T_CT * p_T_[r], &px)) continue;
                  bool found = false;
                  for (int d = 0; d < n_detections; ++d) {
                    // A detection that made the candidate already belongs to one of its LEDs;
                    // letting it vote again mostly counts near-miss relabellings.
                    if (d == a || d == b || d == c) continue;
                    if ((detections[d].px - px).squaredNorm() < threshold_sq) {
                      remaining_votes.push_back({r, d});
                      found = true;
                    }
                  }
                  matched += found ? 1 : 0;
                }
                if (matched == 0) continue;
                max_matched = std::max(max_matched, matched);
                consistent.push_back({d3, {i, j, l}, matched, first_vote, remaining_votes.size()});
              }
            }
          }
        }
      }
    }
  }
  // Only the most consistent candidates vote: with compact targets, a wrong labelling often
  // reprojects one remaining LED near some detection by chance, rarely all of them.
  for (const Candidate& candidate : consistent) {
    if (candidate.matched_leds < max_matched) continue;
    for (std::size_t v = candidate.first_vote; v < candidate.end_vote; ++v) {
      ++votes(remaining_votes[v].led, remaining_votes[v].detection);
    }
    for (int k = 0; k < 3; ++k) ++votes(candidate.l3[k], candidate.d3[k]);
  }
  // Greedy extraction (Fig. C.5): highest bin first, each LED (row) once.
  const double min_votes = params_.acceptance_ratio * Choose3(n_leds);
  std::vector<bool> led_taken(n_leds, false);
  while (n_detections > 0) {
    int best_led = -1, best_detection = -1, best_votes = -1;
    for (int led = 0; led < n_leds; ++led) {
      if (led_taken[led]) continue;
      for (int d = 0; d < n_detections; ++d) {
        if (votes(led, d) > best_votes) {
          best_votes = votes(led, d);
          best_led = led;
          best_detection = d;
        }
      }
    }
    if (best_led < 0 || best_votes < min_votes) break;
    led_taken[best_led] = true;
    result.correspondences.push_back({best_led, best_detection});
  }
  std::sort(result.correspondences.begin(), result.correspondences.end(),
            [](const LedCorrespondence& x, const LedCorrespondence& y) { return x.led < y.led; });
  result.T_CT = BestCandidate(result.correspondences, detections, camera);
  // Votes never pair an LED with a detection that made the candidate, so an LED whose blob
  // merged with another one's gets too few votes: give every LED left over the nearest detection
  // within lambda_r of its reprojection from the best candidate (shared detections flag merges).
  if (result.T_CT) {
    for (int led = 0; led < n_leds; ++led) {
      Eigen::Vector2d px;
      if (led_taken[led] || !camera.Project(*result.T_CT * p_T_[led], &px)) continue;
      int nearest = -1;
      double nearest_sq = threshold_sq;
      for (int d = 0; d < n_detections; ++d) {
        const double distance_sq = (detections[d].px - px).squaredNorm();
        if (distance_sq < nearest_sq) {
          nearest_sq = distance_sq;
          nearest = d;
        }
      }
      if (nearest >= 0) result.correspondences.push_back({led, nearest});
    }
    std::sort(result.correspondences.begin(), result.correspondences.end(),
              [](const LedCorrespondence& x, const LedCorrespondence& y) { return x.led < y.led; });
  }
  if (histogram) *histogram = votes;
  return result;
}

LedCorrespondenceResult LedCorrespondenceSearch::Verify(
    const std::vector<LedCorrespondence>& correspondences,
    const std::vector<LedDetection>& detections, const CameraModel& camera) const {
  LedCorrespondenceResult result;
  result.correspondences = correspondences;
  const int n = static_cast<int>(correspondences.size());
  if (n < 4) return result;
  const double threshold_sq = params_.reprojection_threshold_px * params_.reprojection_threshold_px;
  std::vector<Eigen::Isometry3d> candidates;
  std::array<Eigen::Vector3d, 3> f_C, p_T;
  int subsets = 0, passed = 0;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      for (int c = b + 1; c < n; ++c) {
        const std::array<int, 3> s{a, b, c};
        for (int k = 0; k < 3; ++k) {
          f_C[k] = detections[correspondences[s[k]].detection].f_C;
          p_T[k] = p_T_[correspondences[s[k]].led];
        }
        ++subsets;
        SolveP3p(params_.p3p_method, f_C, p_T, &candidates);
        result.pose_candidates += static_cast<int>(candidates.size());
        for (const Eigen::Isometry3d& T_CT : candidates) {
          int inliers = 0;
          for (int r = 0; r < n; ++r) {
            if (r == a || r == b || r == c) continue;
            Eigen::Vector2d px;
            if (camera.Project(T_CT * p_T_[correspondences[r].led], &px) &&
                (detections[correspondences[r].detection].px - px).squaredNorm() < threshold_sq) {
              ++inliers;
            }
          }
          if (inliers >= params_.min_inlier_ratio * (n - 3)) {
            ++passed;
            break;
          }
        }
      }
    }
  }
  result.verified_ratio = static_cast<double>(passed) / subsets;
  result.verified = result.verified_ratio > params_.min_subset_ratio;
  if (result.verified) result.T_CT = BestCandidate(correspondences, detections, camera);
  return result;
}

std::optional<Eigen::Isometry3d> LedCorrespondenceSearch::BestCandidate(
    const std::vector<LedCorrespondence>& correspondences,
    const std::vector<LedDetection>& detections, const CameraModel& camera) const {
  const int n = static_cast<int>(correspondences.size());
  std::optional<Eigen::Isometry3d> best;
  double best_error = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Isometry3d> candidates;
  std::array<Eigen::Vector3d, 3> f_C, p_T;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      for (int c = b + 1; c < n; ++c) {
        const std::array<int, 3> s{a, b, c};
        const int da = correspondences[a].detection, db = correspondences[b].detection,
                  dc = correspondences[c].detection;
        if (da == db || db == dc || da == dc) continue;
        for (int k = 0; k < 3; ++k) {
          f_C[k] = detections[correspondences[s[k]].detection].f_C;
          p_T[k] = p_T_[correspondences[s[k]].led];
        }
        SolveP3p(params_.p3p_method, f_C, p_T, &candidates);
        for (const Eigen::Isometry3d& T_CT : candidates) {
          double error = 0.0;
          for (const LedCorrespondence& correspondence : correspondences) {
            Eigen::Vector2d px;
            if (!camera.Project(T_CT * p_T_[correspondence.led], &px)) {
              error = std::numeric_limits<double>::infinity();
              break;
            }
            error += (detections[correspondence.detection].px - px).squaredNorm();
          }
          if (error < best_error) {
            best_error = error;
            best = T_CT;
          }
        }
      }
    }
  }
  return best;
}

}  // namespace aperture::perception
