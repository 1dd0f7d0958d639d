#pragma once
// Per-patch monocular depth cues of seed 003 Sec. III-A (after Saxena et al. [17]): the image is
// cut into a grid of square patches and every patch gets the 102-vector
//
//   E_i(n) = mean_{(x,y) in window_s(i)} |I(x,y) * F_n(x,y)|^k,  n = 1..17, k = 1, 2, s = 0, 1, 2
//
// with the 17 filters F_n: the 9 Laws' masks (outer products of L3 = [1 2 1], E3 = [-1 0 1],
// S3 = [-1 2 -1]) on the intensity Y (texture energy), the local average (L3 L3) of the colour
// channels Cr and Cb (haze), and 6 edge filters oriented at 0, 30, ..., 150 deg on Y (texture
// gradient; steered first derivatives of a 5x5 binomial Gaussian). The paper sums over the patch;
// we take the mean so the features do not depend on the patch area. Scale s filters the image
// downsampled by scale_factor^s and averages over a window of patch_px level pixels centred on the
// patch, i.e. over scale_factor^s times the patch's extent (the paper's "three scale-image
// resolutions" that add global context). Layout of one row of Features: [s][k][n] =
// s * 34 + (k - 1) * 17 + n.
//
// Speed: all filters are separable 3- or 5-tap kernels run on a work image of work_width_px
// columns; the window means come from one integral image per map (O(1) per patch).
#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

namespace aperture::perception {

struct MonoDepthFeatureParams {
  // The frame is first resized to this width (aspect kept). 320 px keeps the cues of a 640x480
  // frame's trunks and bark while the 17 filters stay a few ms on one core.
  int work_width_px = 320;
  // Patch side at the work resolution: 8 px gives a 40 x 30 grid at 320 x 240, dense enough to
  // resolve a 0.2 m trunk at 5 m with a 90 deg lens.
  int patch_px = 8;
  // Resolution ratio between successive scales (Saxena [17] uses 3: patch, 3x3 and 9x9 patches).
  int scale_factor = 3;

  // Throws std::invalid_argument naming the field when a value is out of range.
  void Validate() const;
};

// The patch grid of one frame: rows x cols patches of patch_px work pixels; in frame pixels a
// patch spans [col, col + 1) * frame_patch_px.x() horizontally (the right/bottom remainder of the
// frame that does not fill a patch is not covered).
struct PatchGrid {
  int rows = 0;
  int cols = 0;
  int work_width_px = 0;
  int work_height_px = 0;
  Eigen::Vector2d frame_patch_px = Eigen::Vector2d::Zero();  // patch size in frame pixels (x, y)
};

class MonoDepthFeatureExtractor {
 public:
  static constexpr int kScales = 3;
  static constexpr int kFilters = 17;
  static constexpr int kFeaturesPerScale = 2 * kFilters;         // 34
  static constexpr int kFeatures = kScales * kFeaturesPerScale;  // 102

  explicit MonoDepthFeatureExtractor(const MonoDepthFeatureParams& params = {});

  // The grid for a frame of `frame_size`; std::invalid_argument when the frame is smaller than one
  // patch at the work resolution.
  PatchGrid Grid(const cv::Size& frame_size) const;

  // `bgr`: CV_8UC3 (BGR) frame. Returns rows*cols x 102 energies, patch (r, c) in row r*cols + c.
  // Throws std::invalid_argument for an empty, gray or non-8-bit image (the colour cues need
  // colour: `aperture run --color`, or a camera rendered with color: true).
  // Reuses internal buffers: not safe to call concurrently on one extractor.
  Eigen::MatrixXf Extract(const cv::Mat& bgr);

  const MonoDepthFeatureParams& params() const { return params_; }

 private:
  // Adds the 34 energies of scale `scale` (level channels y, cr, cb: CV_32F) into `features`.
  void AddScale(int scale, const cv::Mat& y, const cv::Mat& cr, const cv::Mat& cb,
                const PatchGrid& grid, Eigen::MatrixXf& features);

  MonoDepthFeatureParams params_;
  cv::Mat work_bgr_, ycrcb8_, ycrcb_, response_, energy_, integral_;
};

}  // namespace aperture::perception
