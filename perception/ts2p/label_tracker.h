#pragma once
// LabelTracker: tracks a detected opening by foreground/background label sets under FOE
// constraints (seed 002 Sec. III, Alg. 1, Sec. III-A).
//
// From a detection (opening O, its contour C and safe point x_s in frame F^i):
//   F = (O ⊕ eps1) − (O ⊕ eps2)  a ring of the near wall around the opening (circular kernels),
//   B = O ⊖ eps3                 the far background well inside the opening;
// KLT corners C_F, C_B in each. Per frame (Alg. 1), for each set independently:
//   1. track the corners F^i -> F^j (pyramidal Lucas-Kanade);
//   2-5. least squares for the expansion about the FOE, Delta = alpha (x - x_0): the paper fits
//        alpha and beta = alpha x_0 on the x-components (steps 2-4) and takes y_0 from the
//        y-components (step 5); here both components enter one linear least-squares problem
//        [x 1 0; y 0 1] [alpha; c_x; c_y] = [Delta x; Delta y] (c = -alpha x_0, so the fit also
//        holds for alpha -> 0, a pure translation, where the FOE is undefined), re-weighted
//        (up to 5 passes) rejecting corners beyond 3 median residuals (corners on the other
//        depth);
//   6.   propagate the set: x -> (1 + alpha) x + c (composed since the detection, so the masks
//        are warped only to re-detect corners).
// Sets reset their corners (inside the propagated set) when at most k_F / k_B survive. Each set
// carries x_s with it (the FOE scaling preserves the cross-ratios, Sec. III-A); the output x_s is
// the foreground set's when |F| >= |B| in the image, else the background set's, smoothed by
// SafePointFilter. The contour C is not switched with x_s (beyond the paper): it is the rim of
// the opening, an edge of the near wall, so it follows F's fit on every frame where that fit
// holds and B's only where it does not. Taken from B once |B| > |F| (the opening fills the view
// on the approach), C would grow with the far background, slower than the opening itself.
//
// Inputs: 8-bit gray frames of one size, times increasing. Initialize throws
// std::invalid_argument for an empty opening or a size mismatch.
#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>
#include <vector>

#include "config/param_reader.h"
#include "perception/ts2p/opening_track.h"
#include "perception/ts2p/safe_point_filter.h"

namespace aperture::perception {

struct LabelTrackerParams {
  // Kernel radii [px at 576 px width, scaled with the image]: F is the wall ring 8-40 px outside
  // O (outside the uncertainty zone U of a slightly dilated detection, wide enough for ~100
  // corners), B is O eroded by 8 px.
  double foreground_outer_radius_px = 40.0;  // eps1
  double foreground_inner_radius_px = 8.0;   // eps2
  double background_erosion_px = 8.0;        // eps3
  int foreground_min_corners = 40;           // k_F (paper, all experiments)
  int background_min_corners = 20;           // k_B
  int max_corners = 150;                     // per set at a (re)set
  double corner_quality = 0.01;              // goodFeaturesToTrack quality level
  double corner_min_distance_px = 6.0;
  int klt_window_px = 21;
  int klt_pyramid_levels = 3;
  // |alpha| below this: the FOE is reported as NaN (it is at infinity; propagation still holds).
  double min_divergence_for_foe = 1.0e-5;
  SafePointFilterParams filter;

  void Validate() const;
};

void LoadParams(config::ParamReader& reader, SafePointFilterParams* params);  // section `filter`
void LoadParams(config::ParamReader& reader, LabelTrackerParams* params);

// Alg. 1 steps 2-5: the expansion x -> (1 + alpha) x + offset fitted to corner tracks.
struct ExpansionFit {
  bool ok = false;     // >= 3 tracks and a well-conditioned system
  double alpha = 0.0;  // divergence per frame
  Eigen::Vector2d offset_px = Eigen::Vector2d::Zero();
  Eigen::Vector2d foe_px = Eigen::Vector2d::Zero();  // x_0 = -offset / alpha; NaN if undefined
  int inliers = 0;
  std::vector<bool> inlier;  // per track
  Eigen::Vector2d Apply(const Eigen::Vector2d& p) const { return (1.0 + alpha) * p + offset_px; }
};
ExpansionFit FitExpansion(const std::vector<Eigen::Vector2d>& before,
                          const std::vector<Eigen::Vector2d>& after, double min_divergence_for_foe);

class LabelTracker {
 public:
  explicit LabelTracker(const LabelTrackerParams& params);

  // Starts from a detection in `gray` (the detection's reference frame): `opening` CV_8UC1.
  void Initialize(const cv::Mat& gray, const cv::Mat& opening, const Eigen::Vector2d& x_s_px,
                  const std::vector<cv::Point>& contour, double t_s, int index);
  bool initialized() const { return initialized_; }

  // Propagates both sets into `gray` (the next frame).
  OpeningTrack Track(const cv::Mat& gray, double t_s, int index);

  // The current label masks (CV_8UC1), for overlays and tests.
  cv::Mat ForegroundMask() const { return sets_[0].Mask(image_size_); }
  cv::Mat BackgroundMask() const { return sets_[1].Mask(image_size_); }
  const std::vector<cv::Point2f>& ForegroundCorners() const { return sets_[0].corners; }
  const std::vector<cv::Point2f>& BackgroundCorners() const { return sets_[1].corners; }

 private:
  struct LabelSet {
    cv::Mat initial_mask;        // the set in the detection frame
    cv::Mat initial_mask_small;  // 1/4 resolution, for |set| in the image each frame
    double scale = 1.0;          // composed propagation since the detection: x -> s x + o
    Eigen::Vector2d offset_px = Eigen::Vector2d::Zero();
    Eigen::Vector2d x_s_px = Eigen::Vector2d::Zero();
    std::vector<cv::Point2f> corners;
    ExpansionFit last_fit;
    cv::Mat Mask(const cv::Size& size) const;
    double AreaInImage() const;
  };
  void DetectCorners(const cv::Mat& gray, LabelSet* set) const;
  int Radius(double radius_576_px) const;

  LabelTrackerParams params_;
  SafePointFilter filter_;
  bool initialized_ = false;
  cv::Size image_size_;
  std::vector<cv::Mat> previous_pyramid_;
  LabelSet sets_[2];                         // F, B
  std::vector<Eigen::Vector2d> contour_px_;  // C, propagated with F's fit (B's if F's fails)
};

}  // namespace aperture::perception
