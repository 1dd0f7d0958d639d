#include "perception/led/led_correspondence_search.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace aperture::perception {
namespace {

int Choose3(int n) { return n * (n - 1) * (n - 2) / 6; }

// LED `led` seen as detection `detection` in a labelling word (8 bits per LED).
std::uint64_t Label(int led, int detection) {
  return static_cast<std::uint64_t>(detection + 1) << (8 * led);
}

}  // namespace

LedCorrespondenceSearch::LedCorrespondenceSearch(const std::vector<Eigen::Vector3d>& p_T,
                                                 const LedCorrespondenceParams& params)
    : p_T_(p_T), params_(params) {}

LedCorrespondenceResult LedCorrespondenceSearch::FindByBruteForce(
    const std::vector<LedDetection>& detections, const CameraModel& camera,
    Eigen::MatrixXi* histogram) const {
  const int n_leds = static_cast<int>(p_T_.size());
  const int n_detections = static_cast<int>(detections.size());
  if (n_detections > kMaxDetections) {
    throw std::invalid_argument("LedCorrespondenceSearch::FindByBruteForce: " +
                                std::to_string(n_detections) + " detections, at most " +
                                std::to_string(kMaxDetections) +
                                "; cap them with LedDetectorParams.max_blobs");
  }
  Eigen::MatrixXi votes = Eigen::MatrixXi::Zero(n_leds, n_detections);
  LedCorrespondenceResult result;
  const double threshold_sq = params_.reprojection_threshold_px * params_.reprojection_threshold_px;
  std::vector<Eigen::Isometry3d> candidates;
  candidates.reserve(4);
  std::array<Eigen::Vector3d, 3> f_C, p_T;
  // Every candidate that explains at least as many remaining LEDs as the best so far, with its
  // votes (Algorithm 1) and its labelling: the detection (+1, 0 = none) of every LED, 8 bits per
  // LED (kMaxLeds = 8), the remaining LEDs with their nearest detection within lambda_r.
  struct Vote {
    int led, detection;
  };
  struct Candidate {
    Eigen::Isometry3d T_CT;
    std::array<int, 3> d3, l3;
    int matched_leds;  // remaining LEDs with a detection within lambda_r
    std::uint64_t labelling;
    double error_sq;  // sum of the matched remaining LEDs' squared reprojection errors [px^2]
    std::size_t first_vote, end_vote;
  };
  std::vector<Candidate> consistent;
  std::vector<Vote> remaining_votes;
  int max_matched = 1;
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
              const std::uint64_t triple_labelling = Label(i, a) | Label(j, b) | Label(l, c);
              for (const Eigen::Isometry3d& T_CT : candidates) {
                const std::size_t first_vote = remaining_votes.size();
                std::uint64_t labelling = triple_labelling;
                int matched = 0;
                double error_sq = 0.0;
                for (int r = 0; r < n_leds; ++r) {
                  if (r == i || r == j || r == l) continue;
                  Eigen::Vector2d px;
                  if (!camera.Project(T_CT * p_T_[r], &px)) continue;
                  int nearest = -1;
                  double nearest_sq = threshold_sq;
                  for (int d = 0; d < n_detections; ++d) {
                    // A detection that made the candidate already belongs to one of its LEDs;
                    // letting it vote again mostly counts near-miss relabellings.
                    if (d == a || d == b || d == c) continue;
                    const double distance_sq = (detections[d].px - px).squaredNorm();
                    if (distance_sq < threshold_sq) {
                      remaining_votes.push_back({r, d});
                      if (distance_sq < nearest_sq) {
                        nearest_sq = distance_sq;
                        nearest = d;
                      }
                    }
                  }
                  if (nearest >= 0) {
                    ++matched;
                    error_sq += nearest_sq;
                    labelling |= Label(r, nearest);
                  }
                }
                // Early rejection: fewer explained LEDs than the best candidate never vote.
                if (matched < max_matched) {
                  remaining_votes.resize(first_vote);
                  continue;
                }
                max_matched = matched;
                consistent.push_back({T_CT, d3, {i, j, l}, matched, labelling, error_sq,
                                      first_vote, remaining_votes.size()});
              }
            }
          }
        }
      }
    }
  }
  // Only the most consistent candidates vote: with compact targets and lambda_r = 5 px, a wrong
  // labelling often reprojects a remaining LED near some detection by chance, but such a
  // coincidence is not reproduced by P3P on another 3-subset of the same labelling, while the
  // true labelling of m LEDs is reproduced by all C(m, 3) of its 3-subsets. So the voters are the
  // candidates that explain the most LEDs with the labelling most candidates (>= 2) share; among
  // equally shared labellings (a 4-LED subset can mimic another within lambda_r) the one with the
  // smallest mean squared reprojection error of the explained LEDs.
  std::sort(consistent.begin(), consistent.end(), [](const Candidate& x, const Candidate& y) {
    return x.matched_leds != y.matched_leds ? x.matched_leds > y.matched_leds
                                            : x.labelling < y.labelling;
  });
  // Groups of candidates sharing a labelling among those explaining max_matched LEDs.
  struct LabellingGroup {
    std::size_t first, end;
    double mean_error_sq;
  };
  std::vector<LabellingGroup> groups;
  std::size_t best_first = 0, best_end = 0;
  double best_error = std::numeric_limits<double>::infinity();
  for (std::size_t first = 0;
       first < consistent.size() && consistent[first].matched_leds == max_matched;) {
    std::size_t end = first;
    double error_sq = 0.0;
    while (end < consistent.size() && consistent[end].matched_leds == max_matched &&
           consistent[end].labelling == consistent[first].labelling) {
      error_sq += consistent[end++].error_sq;
    }
    const std::size_t support = end - first, best_support = best_end - best_first;
    error_sq /= static_cast<double>(support);
    groups.push_back({first, end, error_sq});
    if (support >= 2 &&
        (support > best_support || (support == best_support && error_sq < best_error))) {
      best_first = first;
      best_end = end;
      best_error = error_sq;
    }
    first = end;
  }
  // The runner-up labelling: the smallest mean squared error among the other groups, whatever
  // their support (a wrong labelling that fits as well is a risk even when few subsets
  // reproduce it).
  const LabellingGroup* runner_up = nullptr;
  for (const LabellingGroup& group : groups) {
    if (best_end > best_first && group.first == best_first) continue;
    if (!runner_up || group.mean_error_sq < runner_up->mean_error_sq) runner_up = &group;
  }
  if (best_end > best_first && runner_up) {
    const Candidate* closest = &consistent[runner_up->first];
    for (std::size_t v = runner_up->first; v < runner_up->end; ++v) {
      if (consistent[v].error_sq < closest->error_sq) closest = &consistent[v];
    }
    result.runner_up_T_CT = closest->T_CT;
    for (int led = 0; led < n_leds; ++led) {
      const int detection = static_cast<int>((closest->labelling >> (8 * led)) & 0xff) - 1;
      if (detection >= 0) result.runner_up_correspondences.push_back({led, detection});
    }
  }
  for (std::size_t v = best_first; v < best_end; ++v) {
    const Candidate& candidate = consistent[v];
    for (std::size_t w = candidate.first_vote; w < candidate.end_vote; ++w) {
      ++votes(remaining_votes[w].led, remaining_votes[w].detection);
    }
    for (int k = 0; k < 3; ++k) ++votes(candidate.l3[k], candidate.d3[k]);
  }
  // Greedy extraction (Fig. C.5): highest bin first, each LED (row) once. The acceptance is
  // 0.5 C(m, 3) with m = 3 + max_matched the number of LEDs the voting candidates explain: the
  // true bins hold C(m, 3) votes, so with m = n_L this is the thesis' 0.5 C(n_L, 3), and with an
  // LED occluded (m = n_L - 1) the four visible ones still pass (0.5 C(5, 3) = 5 would reject
  // their 4 votes and leave a fresh start without a pose).
  const double min_votes = params_.acceptance_ratio * Choose3(3 + max_matched);
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
  result.T_CT = BestCandidate(result.correspondences, detections, camera);
  // A bin filled by chance votes (e.g. the row of an occluded LED) is not reproduced by the
  // consensus pose: keep only the correspondences within lambda_r of it.
  if (result.T_CT) {
    std::vector<LedCorrespondence> consistent_correspondences;
    for (const LedCorrespondence& c : result.correspondences) {
      Eigen::Vector2d px;
      if (camera.Project(*result.T_CT * p_T_[c.led], &px) &&
          (detections[c.detection].px - px).squaredNorm() < threshold_sq) {
        consistent_correspondences.push_back(c);
      } else {
        led_taken[c.led] = false;
      }
    }
    result.correspondences = std::move(consistent_correspondences);
  }
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
  }
  std::sort(result.correspondences.begin(), result.correspondences.end(),
            [](const LedCorrespondence& x, const LedCorrespondence& y) { return x.led < y.led; });
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
  const double threshold_sq = params_.reprojection_threshold_px * params_.reprojection_threshold_px;
  std::optional<Eigen::Isometry3d> best;
  int best_inliers = 0;
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
          // Consensus first (correspondences within lambda_r), then their squared error: one
          // wrong correspondence must not drag the choice to a compromise pose.
          int inliers = 0;
          double error = 0.0;
          for (const LedCorrespondence& correspondence : correspondences) {
            Eigen::Vector2d px;
            if (!camera.Project(T_CT * p_T_[correspondence.led], &px)) continue;
            const double error_sq = (detections[correspondence.detection].px - px).squaredNorm();
            if (error_sq >= threshold_sq) continue;
            ++inliers;
            error += error_sq;
          }
          if (inliers > best_inliers || (inliers == best_inliers && error < best_error)) {
            best_inliers = inliers;
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
