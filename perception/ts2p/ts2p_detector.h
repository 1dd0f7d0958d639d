#pragma once
// Ts2pDetector: unknown-gap detection by Temporally Stacked Spatial Parallax (seed 002, GapFlyt,
// Sec. II). A short lateral scan gives a reference frame F^i (the gap fully visible) and N other
// frames; with Omega ~ 0 and V_z << V_x, V_y the flow magnitude is inverse depth times the
// baseline (Sec. II, eq. for p_x), so the near foreground wall F moves more than the background
// B seen through the opening.
//
//   1. dense flow reference -> each frame (DenseFlow, by name);
//   2. optional gyro derotation (beyond the paper), before the flow: each frame is resampled
//      into the reference camera's orientation, pixel x taking the frame's value at
//      Project(R_CkCr * Unproject(x)) (the rotational flow predicted through the camera model),
//      so the flow method sees the translational parallax only and the scan need not be
//      rotation-free (only when R_CkCr is given; off for sequences without an IMU). Pixels whose
//      rotated ray leaves the frame carry no parallax (NaN in the stack);
//   3. stacked mean magnitude ||xi_i p_x|| = (1/N) sum_k ||flow_k(x)|| (Sec. II: noise ~ N^-1/2),
//      its inverse and the spatial derivative Xi = |grad ||xi_i p_x||^-1| (Sec. II);
//   3b. edge-aware refinement of the stacked magnitude (beyond the paper): the fast global
//      smoother (Min et al. 2014, weighted least squares, eq. 1) guided by the reference image.
//      Where the reference has no texture (a thin spike of a smooth background, a blank patch of
//      the wall) the flow is unobservable and patch-based flow fills it from the strongest
//      nearby structure, usually the wall's edge moving with F; the smoother instead fills it
//      from the pixels of similar intensity it is connected to, and does not cross the intensity
//      edge that a depth edge almost always is. `edge_aware_lambda = 0` turns it off;
//   4. segmentation of the opening O, one of
//      - "region" (default): the flow map is bimodal (F and B modes, iterative two-means /
//        isodata); the low-flow component at / nearest the image centre, holes filled, a small
//        opening/closing against flow speckle. Flow bleeds across a depth edge (patch-based
//        methods) and is filled in from the wall where the reference is occluded in a frame,
//        which biases the opening's rim towards F: the threshold sits threshold_fraction of the
//        way from B to F. When the low side touches the image border (something nearer than the
//        wall, e.g. the ground, took the F mode), the low side is split again.
//      - "edges" (the paper, Sec. IV-B: "a canny edge detector is run on Xi followed by
//        morphological operations"): Canny on the normalized inverse flow, closing, the enclosed
//        region at / nearest the centre, eroded back by the closing radius.
//   5. contour C of O and the safe point x_s = argmin_x sum_{o in O} ||o - x|| (Sec. III-A, the
//      geometric median, Weiszfeld iterations).
//
// Inputs: 8-bit gray or BGR images of one size; rotations R_CkCr map reference-camera vectors
// into camera k (p_Ck = R_CkCr p_Cr, e.g. integrated gyro rates through R_BC). Outputs in the
// reference frame's pixels. Bad input throws std::invalid_argument; a scan without usable
// parallax returns a detection with valid == false and the reason in `status`.
#include <Eigen/Core>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "config/param_reader.h"
#include "perception/camera/camera_model.h"
#include "perception/flow/dense_flow.h"

namespace aperture::perception {

// DIS-medium without DIS's own variational refinement: the edge-aware refinement (step 3b) does
// that job on the stacked map, and the flow costs ~25 % less (docs/results/ts2p.md).
inline DenseFlowParams Ts2pDefaultFlow() {
  DenseFlowParams flow;
  flow.method = "dis_medium";
  flow.dis_refinement_iterations = 0;
  return flow;
}

struct Ts2pParams {
  DenseFlowParams flow = Ts2pDefaultFlow();  // section `flow`
  // Flow is computed on images resized by this factor (1 = full resolution); the maps and O are
  // returned at full resolution. 1 keeps the contour sharp; 0.5 quarters the flow time.
  double flow_scale = 1.0;
  std::string segmentation = "region";  // region | edges
  // Below this stacked parallax [px at 576 px width, scaled with the image] between the F and B
  // modes the scan gave no structure (e.g. hovering or a pure rotation after derotation): no
  // detection. 1 px is well above DIS's ~0.1 px noise on static textured frames.
  double min_mode_separation_px = 1.0;
  // Morphology radius [px at 576x384, scaled with the image width] against flow speckle; small
  // against any gap the vehicle can pass (tens of px).
  double morphology_radius_px = 3.0;
  // Region threshold between the two flow modes, as a fraction of the way from B to F. 0.5 is
  // the isodata midpoint; a pixel of the opening next to its contour is occluded (its flow is
  // then filled in from the wall) in up to half the stack's frames and receives the wall's flow
  // through the methods' smoothing, which biases it towards F, so the default sits above 0.5.
  // 0.8: on the bench's first 20 trials (seed 1) DR 0.85 / AFN 0.11 against 0.80 / 0.14 at
  // 0.7 and lower at 0.5 (docs/results/ts2p.md); AFP stays ~0.002.
  double threshold_fraction = 0.8;
  // Hysteresis (beyond the paper): when > 0, O as found at threshold_fraction decides that there
  // is an opening, and O is then narrowed to its part below this lower fraction (the component
  // at / nearest the centre) if that keeps at least min_core_fraction of O's area. The inclusive
  // threshold finds small openings; the lower one drops humps of wall whose parallax the flow
  // smoothed towards B, which a vehicle aiming at O's centroid flies into. 0 = off (bench ts2p
  // scores the paper's O); the GapFlyt mission flies the core (planning/gapflyt).
  double core_threshold_fraction = 0.0;
  double min_core_fraction = 0.5;
  // O must cover this fraction of the image, else no detection (a speckle, not a gap).
  double min_area_fraction = 0.005;
  // Fast global smoother of step 3b: smoothness weight lambda (0 = off) and the range of the
  // guide's gray levels over which pixels smooth into each other. 100 / 8 with the default flow:
  // DR 0.97 / 0.98 over 150 trials of seeds 1 / 2 (0.85 without, stars 0.23 -> 0.87); lambda 300
  // or sigma 16 change DR by < 0.02 on a 62-trial subset (docs/results/ts2p.md).
  double edge_aware_lambda = 100.0;
  double edge_aware_sigma_color = 8.0;
  // Paper (Sec. IV-B) "edges": Canny thresholds on the inverse flow normalized to 0..255.
  double canny_low = 20.0;
  double canny_high = 60.0;
  int weiszfeld_iterations = 30;

  void Validate() const;
};

void LoadParams(config::ParamReader& reader, Ts2pParams* params);

// Run time of each stage of one detection [ms].
struct Ts2pTiming {
  double flow_ms = 0.0;
  double derotation_ms = 0.0;
  double stacking_ms = 0.0;
  double edge_aware_ms = 0.0;
  double segmentation_ms = 0.0;
  double safe_point_ms = 0.0;
  double total_ms = 0.0;  // wall-clock
  double cpu_ms = 0.0;    // CPU time of the detecting thread (the cost on one core)
};

struct Ts2pDetection {
  bool valid = false;
  std::string status;              // "ok" or why there is no opening
  cv::Mat opening;                 // CV_8UC1, 255 = O (reference pixels); zeros when !valid
  bool core = false;               // O was narrowed to its core (core_threshold_fraction)
  cv::Mat mean_flow_px;            // CV_32FC1 stacked mean flow magnitude [px] (after 3b)
  cv::Mat xi;                      // CV_32FC1 |grad of the inverse mean flow| [1/px per px]
  std::vector<cv::Point> contour;  // C: outer boundary of O [px]
  Eigen::Vector2d safe_point_px = Eigen::Vector2d::Zero();  // x_s, geometric median of O
  double area_px = 0.0;
  double foreground_flow_px = 0.0;  // the two modes of the stacked flow [px]
  double background_flow_px = 0.0;
  int stack_size = 0;
  Ts2pTiming timing;
};

class Ts2pDetector {
 public:
  // `camera` is needed only to derotate (Detect with rotations); may be null otherwise.
  explicit Ts2pDetector(const Ts2pParams& params,
                        std::shared_ptr<const CameraModel> camera = nullptr);

  // `frames`: the N stack frames (N >= 1); R_CkCr empty (no derotation) or one per frame.
  Ts2pDetection Detect(const cv::Mat& reference, const std::vector<cv::Mat>& frames,
                       const std::vector<Eigen::Matrix3d>& R_CkCr = {});

  // Rotational flow of every reference pixel for the rotation R_CkCr (CV_32FC2 [px], the
  // camera's size): Project(R_CkCr Unproject(x)) - x; NaN where the rotated ray leaves the model.
  cv::Mat RotationalFlow(const Eigen::Matrix3d& R_CkCr);

  // Step 2: `frame` (8-bit, the camera's size) resampled into the reference orientation
  // (bilinear); a pure rotation's frame becomes the reference image. *unseen (optional, CV_8UC1)
  // = 255 where the rotated ray falls outside the frame.
  cv::Mat Derotate(const cv::Mat& frame, const Eigen::Matrix3d& R_CkCr, cv::Mat* unseen = nullptr);

  const Ts2pParams& params() const { return params_; }
  std::string FlowName() const { return flow_.Describe(); }

 private:
  // Step 3b on the CV_32FC1 `values` guided by the 8-bit gray `guide`.
  cv::Mat EdgeAwareSmooth(const cv::Mat& guide, const cv::Mat& values) const;
  cv::Mat SegmentRegion(const cv::Mat& mean_flow, double threshold) const;
  cv::Mat SegmentEdges(const cv::Mat& inverse_flow, double inverse_foreground,
                       double inverse_background) const;
  int MorphologyRadius(int image_width) const;

  Ts2pParams params_;
  std::shared_ptr<const CameraModel> camera_;
  DenseFlow flow_;
  cv::Mat bearings_;  // CV_32FC3 unit rays of the camera's pixels (cached for derotation)
};

// Isodata (iterative two-means) threshold of the finite `values` (CV_32FC1): the
// midpoint of the means of the two classes it separates; *low_mean / *high_mean get those means.
double TwoMeansThreshold(const cv::Mat& values, double* low_mean, double* high_mean);

// The main mode of the finite `values` (CV_32FC1) and a separate low tail below it: high = the
// median, cutoff = high - 4 robust spreads (1.4826 x the median absolute deviation), low = the
// median of the values below the cutoff. None when that tail holds fewer than min_fraction of the
// values (it is then the main mode's own spread, not a second mode).
struct LowTailMode {
  double low = 0.0;
  double high = 0.0;
  double cutoff = 0.0;
};
std::optional<LowTailMode> FindLowTailMode(const cv::Mat& values, double min_fraction);

// argmin_x sum_o ||o - x|| over the non-zero pixels of `mask` (Weiszfeld); NaN for an empty mask.
Eigen::Vector2d GeometricMedian(const cv::Mat& mask, int iterations);

}  // namespace aperture::perception
