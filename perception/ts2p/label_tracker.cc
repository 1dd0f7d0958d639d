#include "perception/ts2p/label_tracker.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>

#include "perception/elapsed_time.h"
#include "perception/ts2p/disk_kernel.h"

namespace aperture::perception {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kSmallFactor = 4;  // |set| is counted on masks at 1/4 resolution

// Least squares of [x 1 0; y 0 1] [alpha; c_x; c_y] = [dx; dy] over the tracks with `use`.
bool SolveExpansion(const std::vector<Eigen::Vector2d>& before,
                    const std::vector<Eigen::Vector2d>& after, const std::vector<bool>& use,
                    Eigen::Vector3d* solution) {
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  int count = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (!use[i]) continue;
    const Eigen::Vector2d d = after[i] - before[i];
    const Eigen::Vector3d row_x(before[i].x(), 1.0, 0.0), row_y(before[i].y(), 0.0, 1.0);
    AtA += row_x * row_x.transpose() + row_y * row_y.transpose();
    Atb += row_x * d.x() + row_y * d.y();
    ++count;
  }
  if (count < 3) return false;
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(AtA);
  // Degenerate when all tracks coincide (no spread to separate alpha from the offset).
  if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() < 1e-9 * AtA.trace()) return false;
  *solution = ldlt.solve(Atb);
  return true;
}

}  // namespace

void LabelTrackerParams::Validate() const {
  if (!(foreground_outer_radius_px > foreground_inner_radius_px) ||
      !(foreground_inner_radius_px >= 0.0) || !(background_erosion_px >= 0.0)) {
    throw std::invalid_argument(
        "gap_tracker: need foreground_outer_radius_px > foreground_inner_radius_px >= 0 and "
        "background_erosion_px >= 0");
  }
  if (foreground_min_corners < 3 || background_min_corners < 3 ||
      max_corners <= std::max(foreground_min_corners, background_min_corners)) {
    throw std::invalid_argument(
        "gap_tracker: foreground/background_min_corners must be >= 3 and max_corners above both");
  }
  if (!(corner_quality > 0.0 && corner_quality < 1.0) || !(corner_min_distance_px >= 1.0) ||
      klt_window_px < 5 || klt_pyramid_levels < 0 || !(min_divergence_for_foe > 0.0)) {
    throw std::invalid_argument(
        "gap_tracker: corner_quality in (0, 1), corner_min_distance_px >= 1, klt_window_px >= 5, "
        "klt_pyramid_levels >= 0, min_divergence_for_foe > 0");
  }
  filter.Validate();
}

void LoadParams(config::ParamReader& reader, SafePointFilterParams* params) {
  reader.Read("acceleration_psd", &params->acceleration_psd);
  reader.Read("measurement_sigma_px", &params->measurement_sigma_px);
}

void LoadParams(config::ParamReader& reader, LabelTrackerParams* params) {
  reader.Read("foreground_outer_radius_px", &params->foreground_outer_radius_px);
  reader.Read("foreground_inner_radius_px", &params->foreground_inner_radius_px);
  reader.Read("background_erosion_px", &params->background_erosion_px);
  reader.Read("foreground_min_corners", &params->foreground_min_corners);
  reader.Read("background_min_corners", &params->background_min_corners);
  reader.Read("max_corners", &params->max_corners);
  reader.Read("corner_quality", &params->corner_quality);
  reader.Read("corner_min_distance_px", &params->corner_min_distance_px);
  reader.Read("klt_window_px", &params->klt_window_px);
  reader.Read("klt_pyramid_levels", &params->klt_pyramid_levels);
  reader.Read("min_divergence_for_foe", &params->min_divergence_for_foe);
  reader.ReadSection("filter", &params->filter);
  reader.Validate(*params);
}

ExpansionFit FitExpansion(const std::vector<Eigen::Vector2d>& before,
                          const std::vector<Eigen::Vector2d>& after,
                          double min_divergence_for_foe) {
  if (before.size() != after.size()) {
    throw std::invalid_argument("FitExpansion: " + std::to_string(before.size()) + " and " +
                                std::to_string(after.size()) + " points; tracks come in pairs");
  }
  ExpansionFit fit;
  fit.inlier.assign(before.size(), true);
  Eigen::Vector3d solution;
  if (!SolveExpansion(before, after, fit.inlier, &solution)) return fit;
  // Re-weighting passes: drop tracks beyond 3 median residuals (and 0.5 px, the KLT noise) of
  // the current fit, refit, until the inlier set settles.
  constexpr int kPasses = 5;
  for (int pass = 0; pass < kPasses; ++pass) {
    std::vector<double> residuals(before.size());
    for (std::size_t i = 0; i < before.size(); ++i) {
      const Eigen::Vector2d predicted = (1.0 + solution.x()) * before[i] + solution.tail<2>();
      residuals[i] = (after[i] - predicted).norm();
    }
    std::vector<double> sorted;
    for (std::size_t i = 0; i < before.size(); ++i) {
      if (fit.inlier[i]) sorted.push_back(residuals[i]);
    }
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double gate = std::max(3.0 * sorted[sorted.size() / 2], 0.5);
    std::vector<bool> inlier(before.size());
    for (std::size_t i = 0; i < before.size(); ++i) inlier[i] = residuals[i] <= gate;
    if (inlier == fit.inlier && pass > 0) break;
    fit.inlier = inlier;
    if (!SolveExpansion(before, after, fit.inlier, &solution)) return fit;
  }
  fit.ok = true;
  fit.alpha = solution.x();
  fit.offset_px = solution.tail<2>();
  fit.inliers = static_cast<int>(std::count(fit.inlier.begin(), fit.inlier.end(), true));
  fit.foe_px = std::abs(fit.alpha) >= min_divergence_for_foe
                   ? Eigen::Vector2d(-fit.offset_px / fit.alpha)
                   : Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  return fit;
}

LabelTracker::LabelTracker(const LabelTrackerParams& params)
    : params_(params), filter_(params.filter) {
  params_.Validate();
}

int LabelTracker::Radius(double radius_576_px) const {
  return std::max(1, static_cast<int>(std::lround(radius_576_px * image_size_.width / 576.0)));
}

cv::Mat LabelTracker::LabelSet::Mask(const cv::Size& size) const {
  cv::Mat mask;
  const cv::Matx23d warp(scale, 0.0, offset_px.x(), 0.0, scale, offset_px.y());
  cv::warpAffine(initial_mask, mask, warp, size, cv::INTER_NEAREST);
  return mask;
}

double LabelTracker::LabelSet::AreaInImage() const {
  cv::Mat mask;
  // Same map at 1/4 resolution: x/4 -> s x/4 + o/4.
  const cv::Matx23d warp(scale, 0.0, offset_px.x() / kSmallFactor, 0.0, scale,
                         offset_px.y() / kSmallFactor);
  cv::warpAffine(initial_mask_small, mask, warp, initial_mask_small.size(), cv::INTER_NEAREST);
  return static_cast<double>(cv::countNonZero(mask)) * kSmallFactor * kSmallFactor;
}

void LabelTracker::DetectCorners(const cv::Mat& gray, LabelSet* set) const {
  set->corners.clear();
  const cv::Mat mask = set->Mask(gray.size());
  if (cv::countNonZero(mask) == 0) return;
  cv::goodFeaturesToTrack(gray, set->corners, params_.max_corners, params_.corner_quality,
                          params_.corner_min_distance_px, mask);
}

void LabelTracker::Initialize(const cv::Mat& gray, const cv::Mat& opening,
                              const Eigen::Vector2d& x_s_px, const std::vector<cv::Point>& contour,
                              double t_s, int index) {
  (void)index;
  if (gray.empty() || gray.type() != CV_8UC1 || opening.size() != gray.size() ||
      opening.type() != CV_8UC1 || cv::countNonZero(opening) == 0) {
    throw std::invalid_argument(
        "LabelTracker::Initialize needs a CV_8UC1 frame and a non-empty CV_8UC1 opening of its "
        "size");
  }
  image_size_ = gray.size();
  cv::Mat outer, inner, background;
  cv::dilate(opening, outer, DiskKernel(Radius(params_.foreground_outer_radius_px)));
  cv::dilate(opening, inner, DiskKernel(Radius(params_.foreground_inner_radius_px)));
  cv::erode(opening, background, DiskKernel(Radius(params_.background_erosion_px)));
  sets_[0].initial_mask = outer & ~inner;
  sets_[1].initial_mask = background;
  contour_px_.clear();
  for (const cv::Point& p : contour) contour_px_.emplace_back(p.x, p.y);
  for (LabelSet& set : sets_) {
    cv::resize(set.initial_mask, set.initial_mask_small,
               cv::Size(std::max(1, image_size_.width / kSmallFactor),
                        std::max(1, image_size_.height / kSmallFactor)),
               0, 0, cv::INTER_NEAREST);
    set.scale = 1.0;
    set.offset_px.setZero();
    set.x_s_px = x_s_px;
    set.last_fit = ExpansionFit{};
    DetectCorners(gray, &set);
  }
  cv::buildOpticalFlowPyramid(gray, previous_pyramid_,
                              cv::Size(params_.klt_window_px, params_.klt_window_px),
                              params_.klt_pyramid_levels);
  filter_.Reset(x_s_px, t_s);
  initialized_ = true;
}

OpeningTrack LabelTracker::Track(const cv::Mat& gray, double t_s, int index) {
  OpeningTrack track;
  track.t_s = t_s;
  track.index = index;
  if (!initialized_) return track;
  if (gray.size() != image_size_ || gray.type() != CV_8UC1) {
    throw std::invalid_argument(
        "LabelTracker::Track: frame is not CV_8UC1 of the detection's size");
  }
  auto start = Clock::now();
  std::vector<cv::Mat> pyramid;
  const cv::Size window(params_.klt_window_px, params_.klt_window_px);
  cv::buildOpticalFlowPyramid(gray, pyramid, window, params_.klt_pyramid_levels);
  // Step 1 for both sets in one call.
  std::vector<cv::Point2f> before, after;
  for (const LabelSet& set : sets_)
    before.insert(before.end(), set.corners.begin(), set.corners.end());
  std::vector<unsigned char> status;
  std::vector<float> error;
  if (!before.empty()) {
    cv::calcOpticalFlowPyrLK(previous_pyramid_, pyramid, before, after, status, error, window,
                             params_.klt_pyramid_levels);
  }
  track.klt_ms = MillisecondsSince(start);

  std::size_t first = 0;
  for (int s = 0; s < 2; ++s) {
    LabelSet& set = sets_[s];
    const std::size_t count = set.corners.size();
    auto stage = Clock::now();
    std::vector<Eigen::Vector2d> p_before, p_after;
    std::vector<cv::Point2f> survivors;
    for (std::size_t i = first; i < first + count; ++i) {
      if (!status[i]) continue;
      const cv::Point2f& q = after[i];
      if (q.x < 0 || q.y < 0 || q.x > image_size_.width - 1 || q.y > image_size_.height - 1)
        continue;
      p_before.emplace_back(before[i].x, before[i].y);
      p_after.emplace_back(q.x, q.y);
      survivors.push_back(q);
    }
    first += count;
    set.last_fit = FitExpansion(p_before, p_after, params_.min_divergence_for_foe);
    set.corners.clear();
    if (set.last_fit.ok) {
      const ExpansionFit& fit = set.last_fit;
      for (std::size_t i = 0; i < survivors.size(); ++i) {
        if (fit.inlier[i]) set.corners.push_back(survivors[i]);
      }
      // Step 6, composed: x -> (1 + alpha)(s x + o) + c.
      set.scale *= 1.0 + fit.alpha;
      set.offset_px = fit.Apply(set.offset_px);
      set.x_s_px = fit.Apply(set.x_s_px);
    }
    track.propagation_ms += MillisecondsSince(stage);
    const int k = s == 0 ? params_.foreground_min_corners : params_.background_min_corners;
    const bool reset = static_cast<int>(set.corners.size()) <= k;
    (s == 0 ? track.foreground_corners : track.background_corners) =
        static_cast<int>(set.corners.size());
    if (reset) {
      stage = Clock::now();
      DetectCorners(gray, &set);
      track.klt_ms += MillisecondsSince(stage);
      (s == 0 ? track.foreground_reset : track.background_reset) = true;
    }
  }
  previous_pyramid_ = std::move(pyramid);

  // C is the rim of the opening in the near wall: it moves with F. B's fit stands in only on a
  // frame where F's fails (both failing leave C where it was).
  auto stage = Clock::now();
  const ExpansionFit& rim_fit = sets_[0].last_fit.ok ? sets_[0].last_fit : sets_[1].last_fit;
  if (rim_fit.ok) {
    for (Eigen::Vector2d& p : contour_px_) p = rim_fit.Apply(p);
  }

  // Sec. III-A: x_s from F when |F| >= |B|, else from B (sets as seen in the image).
  const bool use_foreground = sets_[0].AreaInImage() >= sets_[1].AreaInImage();
  const LabelSet& chosen = sets_[use_foreground ? 0 : 1];
  track.safe_point_source = use_foreground ? 'F' : 'B';
  track.safe_point_measured_px = chosen.x_s_px;
  track.safe_point_px = filter_.Update(chosen.x_s_px, t_s);
  track.contour_px = contour_px_;
  track.foe_px = chosen.last_fit.foe_px;
  track.divergence = chosen.last_fit.alpha;
  track.valid = sets_[0].last_fit.ok || sets_[1].last_fit.ok;
  track.propagation_ms += MillisecondsSince(stage);
  return track;
}

}  // namespace aperture::perception
