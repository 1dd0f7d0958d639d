#include "perception/ts2p/ts2p_detector.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/edge_filter.hpp>
#include <optional>
#include <stdexcept>

#include "perception/cpu_time.h"
#include "perception/elapsed_time.h"
#include "perception/ts2p/disk_kernel.h"

namespace aperture::perception {
namespace {

using Clock = std::chrono::steady_clock;

// CPU time of the calling thread [ms]: the cost on one core, whatever else loads the machine.
double ThreadCpuMs() { return 1e3 * ThreadCpuSeconds(); }

cv::Mat GrayOfOneOrThreeChannels(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

// An opening seen whole lies inside the wall; one partly out of view touches one side. A region
// on more than a quarter of the border pixels is the wall itself (or the background around it).
constexpr double kMaxBorderFraction = 0.25;

double BorderFraction(const cv::Mat& mask) {
  const int w = mask.cols, h = mask.rows;
  const double on = cv::countNonZero(mask.row(0)) + cv::countNonZero(mask.row(h - 1)) +
                    cv::countNonZero(mask.col(0)) + cv::countNonZero(mask.col(w - 1));
  return on / (2.0 * (w + h));
}

// Fills the holes of a binary mask: background not connected to the image border becomes 255.
cv::Mat FillHoles(const cv::Mat& mask) {
  cv::Mat padded;
  cv::copyMakeBorder(mask, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
  cv::Mat outside = padded.clone();
  cv::floodFill(outside, cv::Point(0, 0), 255);
  cv::Mat holes;
  cv::bitwise_not(outside, holes);
  cv::bitwise_or(padded, holes, padded);
  return padded(cv::Rect(1, 1, mask.cols, mask.rows)).clone();
}

// The connected component of `mask` containing the image centre, else the one whose nearest
// pixel is closest to it (the gap is "near the center of the foreground", Sec. IV-A).
cv::Mat CentralComponent(const cv::Mat& mask) {
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  if (count <= 1) return cv::Mat::zeros(mask.size(), CV_8U);
  const cv::Point centre(mask.cols / 2, mask.rows / 2);
  int best = labels.at<int>(centre);
  if (best == 0) {
    // Distance of every pixel to the centre, minimum per label.
    std::vector<double> nearest(count, std::numeric_limits<double>::infinity());
    for (int y = 0; y < labels.rows; ++y) {
      const int* row = labels.ptr<int>(y);
      for (int x = 0; x < labels.cols; ++x) {
        if (row[x] == 0) continue;
        const double d = std::hypot(x - centre.x, y - centre.y);
        if (d < nearest[row[x]]) nearest[row[x]] = d;
      }
    }
    best = static_cast<int>(std::min_element(nearest.begin() + 1, nearest.end()) - nearest.begin());
  }
  cv::Mat component = labels == best;
  return component;
}

}  // namespace

cv::Mat Ts2pDetector::EdgeAwareSmooth(const cv::Mat& guide, const cv::Mat& values) const {
  // Step 3b: fast global smoother (Min et al. 2014). NaN (derotated rays that left the model)
  // would spread: smooth the finite values and their indicator and divide (normalized
  // smoothing), NaN stays NaN.
  const cv::Mat finite = values == values;
  const bool all_finite = cv::countNonZero(finite) == static_cast<int>(values.total());
  cv::Mat filled = values.clone();
  if (!all_finite) filled.setTo(0.0f, ~finite);
  cv::Mat smooth;
  cv::ximgproc::fastGlobalSmootherFilter(guide, filled, smooth, params_.edge_aware_lambda,
                                         params_.edge_aware_sigma_color);
  if (all_finite) return smooth;
  cv::Mat weight, smooth_weight;
  finite.convertTo(weight, CV_32F, 1.0 / 255.0);
  cv::ximgproc::fastGlobalSmootherFilter(guide, weight, smooth_weight, params_.edge_aware_lambda,
                                         params_.edge_aware_sigma_color);
  cv::divide(smooth, cv::max(smooth_weight, 1e-6), smooth);
  smooth.setTo(std::numeric_limits<float>::quiet_NaN(), ~finite);
  return smooth;
}

void Ts2pParams::Validate() const {
  flow.Validate();
  if (!(flow_scale > 0.0 && flow_scale <= 1.0)) {
    throw std::invalid_argument("ts2p.flow_scale must be in (0, 1] (1 = full resolution), got " +
                                std::to_string(flow_scale));
  }
  if (segmentation != "region" && segmentation != "edges") {
    throw std::invalid_argument("ts2p.segmentation '" + segmentation +
                                "' is unknown; use region or edges");
  }
  if (!(min_mode_separation_px >= 0.0) || !(morphology_radius_px >= 0.0) ||
      !(threshold_fraction > 0.0 && threshold_fraction < 1.0) ||
      !(min_area_fraction >= 0.0 && min_area_fraction < 1.0)) {
    throw std::invalid_argument(
        "ts2p.min_mode_separation_px and morphology_radius_px must be >= 0, "
        "threshold_fraction in (0, 1) and "
        "min_area_fraction in [0, 1)");
  }
  if (!(core_threshold_fraction >= 0.0 && core_threshold_fraction < threshold_fraction) ||
      !(min_core_fraction > 0.0 && min_core_fraction <= 1.0)) {
    throw std::invalid_argument(
        "ts2p.core_threshold_fraction must be in [0, threshold_fraction) (0 = off) and "
        "min_core_fraction in (0, 1], got " +
        std::to_string(core_threshold_fraction) + " and " + std::to_string(min_core_fraction));
  }
  if (!(edge_aware_lambda >= 0.0 && std::isfinite(edge_aware_lambda)) ||
      !(edge_aware_sigma_color > 0.0)) {
    throw std::invalid_argument(
        "ts2p.edge_aware_lambda must be >= 0 (0 = no edge-aware refinement) and "
        "edge_aware_sigma_color > 0 [gray levels], got " +
        std::to_string(edge_aware_lambda) + " and " + std::to_string(edge_aware_sigma_color));
  }
  if (!(canny_low > 0.0 && canny_high >= canny_low) || weiszfeld_iterations < 1) {
    throw std::invalid_argument(
        "ts2p.canny_low must be > 0 and <= canny_high, weiszfeld_iterations >= 1");
  }
}

void LoadParams(config::ParamReader& reader, Ts2pParams* params) {
  reader.ReadSection("flow", &params->flow);
  reader.Read("flow_scale", &params->flow_scale);
  reader.Read("segmentation", &params->segmentation);
  reader.Read("min_mode_separation_px", &params->min_mode_separation_px);
  reader.Read("morphology_radius_px", &params->morphology_radius_px);
  reader.Read("threshold_fraction", &params->threshold_fraction);
  reader.Read("core_threshold_fraction", &params->core_threshold_fraction);
  reader.Read("min_core_fraction", &params->min_core_fraction);
  reader.Read("min_area_fraction", &params->min_area_fraction);
  reader.Read("edge_aware_lambda", &params->edge_aware_lambda);
  reader.Read("edge_aware_sigma_color", &params->edge_aware_sigma_color);
  reader.Read("canny_low", &params->canny_low);
  reader.Read("canny_high", &params->canny_high);
  reader.Read("weiszfeld_iterations", &params->weiszfeld_iterations);
  reader.Validate(*params);
}

double TwoMeansThreshold(const cv::Mat& values, double* low_mean, double* high_mean) {
  CV_Assert(values.type() == CV_32FC1);
  // Isodata from the mean: t <- (mean below t + mean above t) / 2 until it settles.
  double sum = 0.0, min = std::numeric_limits<double>::infinity(), max = -min;
  std::size_t finite = 0;
  for (int y = 0; y < values.rows; ++y) {
    const float* row = values.ptr<float>(y);
    for (int x = 0; x < values.cols; ++x) {
      if (!std::isfinite(row[x])) continue;
      sum += row[x];
      min = std::min<double>(min, row[x]);
      max = std::max<double>(max, row[x]);
      ++finite;
    }
  }
  if (finite == 0) {
    if (low_mean) *low_mean = std::numeric_limits<double>::quiet_NaN();
    if (high_mean) *high_mean = std::numeric_limits<double>::quiet_NaN();
    return std::numeric_limits<double>::quiet_NaN();
  }
  double threshold = sum / finite, low = min, high = max;
  for (int iteration = 0; iteration < 50; ++iteration) {
    double sum_low = 0.0, sum_high = 0.0;
    std::size_t n_low = 0, n_high = 0;
    for (int y = 0; y < values.rows; ++y) {
      const float* row = values.ptr<float>(y);
      for (int x = 0; x < values.cols; ++x) {
        if (!std::isfinite(row[x])) continue;
        if (row[x] < threshold) {
          sum_low += row[x];
          ++n_low;
        } else {
          sum_high += row[x];
          ++n_high;
        }
      }
    }
    if (n_low == 0 || n_high == 0) break;
    low = sum_low / n_low;
    high = sum_high / n_high;
    const double next = 0.5 * (low + high);
    const bool converged = std::abs(next - threshold) < 1e-4 * (max - min + 1e-12);
    threshold = next;
    if (converged) break;
  }
  if (low_mean) *low_mean = low;
  if (high_mean) *high_mean = high;
  return threshold;
}

std::optional<LowTailMode> FindLowTailMode(const cv::Mat& values, double min_fraction) {
  CV_Assert(values.type() == CV_32FC1);
  std::vector<float> finite;
  finite.reserve(values.total());
  for (int y = 0; y < values.rows; ++y) {
    const float* row = values.ptr<float>(y);
    for (int x = 0; x < values.cols; ++x) {
      if (std::isfinite(row[x])) finite.push_back(row[x]);
    }
  }
  if (finite.empty()) return std::nullopt;
  const auto median = [](std::vector<float> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return static_cast<double>(v[v.size() / 2]);
  };
  LowTailMode mode;
  mode.high = median(finite);
  std::vector<float> deviations(finite.size());
  for (std::size_t i = 0; i < finite.size(); ++i) {
    deviations[i] = static_cast<float>(std::abs(finite[i] - mode.high));
  }
  const double spread = 1.4826 * median(deviations);  // the MAD of a normal distribution
  // Below the main mode by more than kTailSpreads spreads: not the main mode's own tail.
  constexpr double kTailSpreads = 4.0;
  mode.cutoff = mode.high - kTailSpreads * spread;
  std::vector<float> tail;
  for (float v : finite) {
    if (v < mode.cutoff) tail.push_back(v);
  }
  if (tail.empty() || tail.size() < min_fraction * finite.size()) return std::nullopt;
  mode.low = median(tail);
  return mode;
}

Eigen::Vector2d GeometricMedian(const cv::Mat& mask, int iterations) {
  std::vector<cv::Point> all;
  cv::findNonZero(mask, all);
  if (all.empty()) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  // Large sets: every pixel with even coordinates (the median moves by well under a pixel).
  std::vector<cv::Point> points;
  if (all.size() > 10000) {
    for (const cv::Point& p : all) {
      if (p.x % 2 == 0 && p.y % 2 == 0) points.push_back(p);
    }
  } else {
    points = std::move(all);
  }
  // Start at the centroid; Weiszfeld: x <- sum(o / d) / sum(1 / d).
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (const cv::Point& p : points) x += Eigen::Vector2d(p.x, p.y);
  x /= static_cast<double>(points.size());
  for (int iteration = 0; iteration < iterations; ++iteration) {
    Eigen::Vector2d numerator = Eigen::Vector2d::Zero();
    double denominator = 0.0;
    for (const cv::Point& p : points) {
      const Eigen::Vector2d o(p.x, p.y);
      const double d = std::max((o - x).norm(), 1e-3);  // a pixel at x: weight bounded
      numerator += o / d;
      denominator += 1.0 / d;
    }
    const Eigen::Vector2d next = numerator / denominator;
    const bool converged = (next - x).norm() < 1e-3;
    x = next;
    if (converged) break;
  }
  return x;
}

Ts2pDetector::Ts2pDetector(const Ts2pParams& params, std::shared_ptr<const CameraModel> camera)
    : params_(params), camera_(std::move(camera)), flow_(params.flow) {
  params_.Validate();
}

int Ts2pDetector::MorphologyRadius(int image_width) const {
  return std::max(
      1, static_cast<int>(std::lround(params_.morphology_radius_px * image_width / 576.0)));
}

cv::Mat Ts2pDetector::RotationalFlow(const Eigen::Matrix3d& R_CkCr) {
  if (!camera_) {
    throw std::invalid_argument("Ts2pDetector: derotation needs the camera model (--calib)");
  }
  const int width = camera_->width(), height = camera_->height();
  if (bearings_.empty()) {
    bearings_.create(height, width, CV_32FC3);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const Eigen::Vector3d b = camera_->Unproject(Eigen::Vector2d(x, y));
        bearings_.at<cv::Vec3f>(y, x) = cv::Vec3f(b.x(), b.y(), b.z());
      }
    }
  }
  cv::Mat flow(height, width, CV_32FC2);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const cv::Vec3f& b = bearings_.at<cv::Vec3f>(y, x);
      Eigen::Vector2d px;
      if (camera_->Project(R_CkCr * Eigen::Vector3d(b[0], b[1], b[2]), &px)) {
        flow.at<cv::Vec2f>(y, x) = cv::Vec2f(px.x() - x, px.y() - y);
      } else {
        flow.at<cv::Vec2f>(y, x) = cv::Vec2f(nan, nan);
      }
    }
  }
  return flow;
}

cv::Mat Ts2pDetector::Derotate(const cv::Mat& frame, const Eigen::Matrix3d& R_CkCr,
                               cv::Mat* unseen) {
  const cv::Mat rotational = RotationalFlow(R_CkCr);
  // Absolute sampling positions x + rotational(x); NaN (ray left the model) samples the border.
  cv::Mat map(rotational.size(), CV_32FC2);
  for (int y = 0; y < map.rows; ++y) {
    const cv::Vec2f* d = rotational.ptr<cv::Vec2f>(y);
    cv::Vec2f* m = map.ptr<cv::Vec2f>(y);
    for (int x = 0; x < map.cols; ++x) m[x] = cv::Vec2f(x + d[x][0], y + d[x][1]);
  }
  cv::Mat derotated;
  cv::remap(frame, derotated, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  if (unseen) {
    std::vector<cv::Mat> xy;
    cv::split(map, xy);
    // Outside [0, size - 1] (NaN compares false, so it counts as outside).
    const cv::Mat inside = (xy[0] >= 0.0f) & (xy[0] <= frame.cols - 1.0f) & (xy[1] >= 0.0f) &
                           (xy[1] <= frame.rows - 1.0f);
    *unseen = ~inside;
  }
  return derotated;
}

cv::Mat Ts2pDetector::SegmentRegion(const cv::Mat& mean_flow, double threshold) const {
  const int radius = MorphologyRadius(mean_flow.cols);
  cv::Mat low = mean_flow < threshold;  // NaN compares false: not part of O
  cv::morphologyEx(low, low, cv::MORPH_OPEN, DiskKernel(radius));
  cv::Mat opening = FillHoles(CentralComponent(low));
  cv::morphologyEx(opening, opening, cv::MORPH_CLOSE, DiskKernel(radius));
  return opening;
}

cv::Mat Ts2pDetector::SegmentEdges(const cv::Mat& inverse_flow, double inverse_foreground,
                                   double inverse_background) const {
  const int radius = MorphologyRadius(inverse_flow.cols);
  // 0 at the foreground mode's inverse flow, 255 at the background's (clipped): the edge
  // contrast does not depend on the scan's baseline, and speckle of near-zero flow (huge
  // inverse) saturates instead of compressing the rest.
  cv::Mat normalized;
  inverse_flow.convertTo(normalized, CV_8U, 255.0 / (inverse_background - inverse_foreground),
                         -255.0 * inverse_foreground / (inverse_background - inverse_foreground));
  cv::Mat edges;
  cv::Canny(normalized, edges, params_.canny_low, params_.canny_high);
  cv::morphologyEx(edges, edges, cv::MORPH_CLOSE, DiskKernel(2 * radius));
  // Regions enclosed by the closed edges; the one at / nearest the centre is O (then eroded back
  // by the edge band so O ends at the contour's inner side, as the paper's "eroded version").
  cv::Mat enclosed = FillHoles(edges);
  cv::Mat interior;
  cv::subtract(enclosed, edges, interior);
  cv::Mat opening = CentralComponent(interior);
  if (cv::countNonZero(opening) == 0) return opening;
  cv::dilate(opening, opening, DiskKernel(radius));
  return opening;
}

Ts2pDetection Ts2pDetector::Detect(const cv::Mat& reference, const std::vector<cv::Mat>& frames,
                                   const std::vector<Eigen::Matrix3d>& R_CkCr) {
  const auto start = Clock::now();
  if (reference.empty() || frames.empty()) {
    throw std::invalid_argument("Ts2pDetector::Detect needs a reference frame and >= 1 frame");
  }
  if (!R_CkCr.empty() && R_CkCr.size() != frames.size()) {
    throw std::invalid_argument("Ts2pDetector::Detect: " + std::to_string(R_CkCr.size()) +
                                " rotations for " + std::to_string(frames.size()) +
                                " frames; give one per frame or none");
  }
  for (const cv::Mat& frame : frames) {
    if (frame.size() != reference.size()) {
      throw std::invalid_argument("Ts2pDetector::Detect: stack frame " +
                                  std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                                  " differs from the reference " + std::to_string(reference.cols) +
                                  "x" + std::to_string(reference.rows));
    }
  }
  if (!R_CkCr.empty() &&
      (!camera_ || camera_->width() != reference.cols || camera_->height() != reference.rows)) {
    throw std::invalid_argument(
        "Ts2pDetector::Detect: derotation needs a camera model of the frames' size (--calib)");
  }
  Ts2pDetection detection;
  detection.stack_size = static_cast<int>(frames.size());
  const cv::Size full = reference.size();
  const double scale = params_.flow_scale;
  const auto resize = [&](const cv::Mat& image) {
    const cv::Mat gray = GrayOfOneOrThreeChannels(image);
    if (scale == 1.0) return gray;
    cv::Mat small;
    cv::resize(gray, small, cv::Size(), scale, scale, cv::INTER_AREA);
    return small;
  };
  const double cpu_start_ms = ThreadCpuMs();
  const cv::Mat reference_small = resize(reference);
  cv::Mat sum = cv::Mat::zeros(reference_small.size(), CV_32F);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    auto stage = Clock::now();
    cv::Mat frame = frames[k], unseen;
    if (!R_CkCr.empty()) {
      frame = Derotate(frames[k], R_CkCr[k], &unseen);
      if (scale != 1.0) cv::resize(unseen, unseen, reference_small.size(), 0, 0, cv::INTER_NEAREST);
      detection.timing.derotation_ms += MillisecondsSince(stage);
      stage = Clock::now();
    }
    const cv::Mat flow = flow_.Compute(reference_small, resize(frame));
    detection.timing.flow_ms += MillisecondsSince(stage);
    stage = Clock::now();
    std::vector<cv::Mat> uv;
    cv::split(flow, uv);
    cv::Mat magnitude;
    cv::magnitude(uv[0], uv[1], magnitude);
    if (!unseen.empty()) magnitude.setTo(std::numeric_limits<float>::quiet_NaN(), unseen);
    sum += magnitude;
    detection.timing.stacking_ms += MillisecondsSince(stage);
  }
  auto stage = Clock::now();
  // Back to full-resolution pixels (flow magnitudes scale with the image).
  cv::Mat mean_flow = sum / (static_cast<double>(frames.size()) * scale);
  if (scale != 1.0) cv::resize(mean_flow, mean_flow, full, 0, 0, cv::INTER_LINEAR);
  detection.timing.stacking_ms += MillisecondsSince(stage);
  if (params_.edge_aware_lambda > 0.0) {
    stage = Clock::now();
    mean_flow = EdgeAwareSmooth(GrayOfOneOrThreeChannels(reference), mean_flow);
    detection.timing.edge_aware_ms = MillisecondsSince(stage);
  }
  stage = Clock::now();
  cv::Mat inverse_flow;
  cv::divide(1.0, cv::max(mean_flow, 1e-3), inverse_flow, CV_32F);
  cv::Mat dx, dy;
  cv::Sobel(inverse_flow, dx, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(inverse_flow, dy, CV_32F, 0, 1, 3, 1.0 / 8.0);
  cv::magnitude(dx, dy, detection.xi);
  detection.mean_flow_px = mean_flow;
  detection.timing.stacking_ms += MillisecondsSince(stage);

  stage = Clock::now();
  detection.opening = cv::Mat::zeros(full, CV_8U);
  const double width_ratio = full.width / 576.0;  // thresholds are given at 576 px
  // The opening is the lowest-flow mode. When the two-means split separates something nearer
  // than the wall (e.g. the ground in front of it) from wall + opening, the low side covers the
  // image border: split that low side again (at most kMaxSplits times).
  constexpr int kMaxSplits = 3;
  cv::Mat values = mean_flow.clone();
  double core_threshold = std::numeric_limits<double>::quiet_NaN();
  for (int split = 0; split < kMaxSplits; ++split) {
    TwoMeansThreshold(values, &detection.background_flow_px, &detection.foreground_flow_px);
    double separation = detection.foreground_flow_px - detection.background_flow_px;
    // The threshold stays below the main mode's own spread when the opening is a low tail.
    double max_threshold = std::numeric_limits<double>::infinity();
    if (!(separation >= params_.min_mode_separation_px * width_ratio)) {
      // A small opening (a few percent of the image: a star, an opening barely wider than the
      // vehicle, a low resolution) does not pull two-means off the wall's own spread of parallax
      // (perspective across the view), which it then splits in two: look for the opening as a
      // low tail below the wall's mode instead (beyond the paper).
      if (const std::optional<LowTailMode> tail =
              FindLowTailMode(values, params_.min_area_fraction)) {
        detection.background_flow_px = tail->low;
        detection.foreground_flow_px = tail->high;
        separation = tail->high - tail->low;
        max_threshold = tail->cutoff;
      }
    }
    if (!(separation >= params_.min_mode_separation_px * width_ratio)) {
      detection.status = "no parallax: flow modes " + std::to_string(detection.background_flow_px) +
                         " and " + std::to_string(detection.foreground_flow_px) +
                         " px are closer than min_mode_separation_px";
      detection.opening.setTo(0);
      break;
    }
    const double threshold = std::min(
        detection.background_flow_px + params_.threshold_fraction * separation, max_threshold);
    detection.opening = params_.segmentation == "region"
                            ? SegmentRegion(mean_flow, threshold)
                            : SegmentEdges(inverse_flow, 1.0 / detection.foreground_flow_px,
                                           1.0 / std::max(detection.background_flow_px, 1e-3));
    if (BorderFraction(detection.opening) <= kMaxBorderFraction) {
      detection.status = "ok";
      core_threshold =
          std::min(detection.background_flow_px + params_.core_threshold_fraction * separation,
                   max_threshold);
      break;
    }
    detection.status = "no enclosed opening: the low-flow region covers the image border";
    detection.opening.setTo(0);
    values.setTo(std::numeric_limits<float>::quiet_NaN(), mean_flow >= threshold);
  }
  detection.area_px = cv::countNonZero(detection.opening);
  if (detection.status == "ok" && detection.area_px < params_.min_area_fraction * full.area()) {
    detection.status = "no opening: largest candidate " +
                       std::to_string(static_cast<int>(detection.area_px)) +
                       " px is below min_area_fraction";
    detection.opening.setTo(0);
    detection.area_px = 0.0;
  }
  // The decision above is the inclusive O's; the core only narrows what is handed on.
  if (detection.status == "ok" && detection.area_px > 0.0 && params_.segmentation == "region" &&
      params_.core_threshold_fraction > 0.0) {
    const cv::Mat core = SegmentRegion(mean_flow, core_threshold) & detection.opening;
    const int core_area_px = cv::countNonZero(core);
    if (core_area_px >= params_.min_core_fraction * detection.area_px) {
      detection.opening = core;
      detection.area_px = core_area_px;
      detection.core = true;
    }
  }
  detection.timing.segmentation_ms = MillisecondsSince(stage);
  if (detection.status == "ok" && detection.area_px > 0.0) {
    stage = Clock::now();
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(detection.opening.clone(), contours, cv::RETR_EXTERNAL,
                     cv::CHAIN_APPROX_SIMPLE);
    if (!contours.empty()) {
      detection.contour = *std::max_element(
          contours.begin(), contours.end(),
          [](const auto& a, const auto& b) { return cv::contourArea(a) < cv::contourArea(b); });
    }
    detection.safe_point_px = GeometricMedian(detection.opening, params_.weiszfeld_iterations);
    detection.timing.safe_point_ms = MillisecondsSince(stage);
    detection.valid = true;
    detection.status = "ok";
  }
  detection.timing.total_ms = MillisecondsSince(start);
  detection.timing.cpu_ms = ThreadCpuMs() - cpu_start_ms;
  return detection;
}

}  // namespace aperture::perception
