#pragma once
// Resolves the planar pose ambiguity of each tag (TagPose: best and alternative) over time and
// across the tags seen together, instead of trusting the lower reprojection error, which picks
// the mirrored tilt about half the time for small or head-on tags.
//
// Per image, for each tag with two candidates, the first rule that applies decides:
//   unambiguous  ambiguity_ratio <= max_ambiguity_ratio and the alternative's summed squared
//                corner error exceeds the best's by min_error_gap_px2: the image itself decides
//                (best; ImageDecides);
//   coplanar     exactly one candidate's normal z_T (in C) lies within coplanar_tolerance_deg of
//                the normal of a tag decided by the image in the same frame (paper D's tags all
//                lie flat on the ground or on obstacle tops);
//   temporal     the tag was seen within max_track_gap_s: each tag keeps both hypotheses,
//                follows each by rotation (camera motion between frames is small) and sums its
//                squared corner reprojection errors over the frames; the candidate of the
//                hypothesis with the lower sum wins (a sequential likelihood-ratio test: the
//                wrong tilt fits slightly worse on average, so evidence accumulates where a
//                single frame is a coin flip);
//   coplanar     as above, against tags decided by the temporal rule in this frame;
//   lowest_error best.
// Tags with one distinct solution are decided as `single`. State: the last choice per
// (family, id). Not thread-safe; one resolver per image stream.
#include <Eigen/Geometry>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "perception/tags/tag_pose_estimator.h"

namespace aperture::perception {

struct TagFlipResolverParams {
  bool enabled = true;  // false: always `best` (the baseline the bench compares against)
  // IPPE's error ratio below which the image is trusted; head-on tags at 1-4 m in the rendered
  // bench sit at 0.4-1, tags viewed at > 30 deg well below 0.2.
  double max_ambiguity_ratio = 0.25;
  // ... and the alternative's summed squared corner error (4 corners) must exceed the best's by
  // this much [px^2]: a ratio of two errors that are both within the corner noise decides
  // nothing. bench tags (0.1 m tags at ~2.3 m, 13 px wide): gaps of 0.03-0.16 px^2 both when
  // the best is right and when it is the mirrored tilt; 0.25 m tags viewed at 30-40 deg: ~2 px^2.
  double min_error_gap_px2 = 0.25;
  double coplanar_tolerance_deg = 15.0;  // 0 disables the coplanar rule
  double max_track_gap_s = 0.5;          // longer gaps restart the tag's history
};

enum class FlipDecision { kSingle, kUnambiguous, kCoplanar, kTemporal, kLowestError };
std::string FlipDecisionName(FlipDecision decision);

struct FlipChoice {
  bool use_alternative = false;
  FlipDecision decision = FlipDecision::kLowestError;
};

struct TagPoseInImage {
  std::string family;
  int id = -1;
  TagPose pose;
};

// Whether the image alone decides between the two candidates (rule `unambiguous` above); false
// without an alternative.
bool ImageDecides(const TagPose& pose, const TagFlipResolverParams& params);

class TagFlipResolver {
 public:
  // std::invalid_argument for a ratio outside [0, 1], a negative error gap, tolerance or gap.
  explicit TagFlipResolver(const TagFlipResolverParams& params = {});

  // One choice per tag of the image taken at t_s (seconds, non-decreasing between calls).
  std::vector<FlipChoice> Resolve(double t_s, const std::vector<TagPoseInImage>& tags);

 private:
  // Both hypotheses of one tag: their latest rotations and summed squared errors [px^2].
  struct Track {
    Eigen::Matrix3d R_CT[2];
    double cost[2];
    double t_s;
  };
  // Updates (or starts) the tag's track with this frame's candidates; returns true when the
  // alternative belongs to the cheaper hypothesis. *had_history: the track existed before.
  bool UpdateTrack(double t_s, const TagPoseInImage& tag, bool* had_history);
  // Chooses by the normals in `references` (unit z_T in C); false when no unique candidate fits.
  bool ChooseCoplanar(const TagPose& pose, const std::vector<Eigen::Vector3d>& references,
                      FlipChoice* choice) const;

  TagFlipResolverParams params_;
  std::map<std::pair<std::string, int>, Track> tracks_;
};

}  // namespace aperture::perception
