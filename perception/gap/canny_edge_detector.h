#pragma once
// Canny edges (3x3 Sobel, L1 gradient magnitude |dx| + |dy|, non-maximum suppression in four
// sectors, 8-connected hysteresis) giving exactly the edges of OpenCV's
// cv::Canny(gray(roi), edges, low, high) (aperture 3, L2gradient = false), optionally followed by
// the 3x3 dilation of cv::dilate(edges, edges, cv::Mat()).
//
// Why not cv::Canny: it runs non-maximum suppression on every pixel above the low threshold, and on
// textured ground (grass, foliage) most pixels are; that made it 60 % of the gap detector's time.
// Here non-maximum suppression is evaluated lazily, only on the pixels the hysteresis reaches from
// a strong seed (magnitude above the high threshold), so after one vectorizable gradient pass the
// cost grows with the number of edge pixels instead of the number of textured pixels. The edge set
// is order independent (a candidate is an edge iff it is 8-connected through candidates to a
// strong candidate), hence identical to OpenCV's.
//
// As cv::Canny does with a sub-matrix, the ROI is treated as an image of its own: the Sobel
// filter replicates the ROI's border pixels, and the magnitude outside the ROI counts as 0 in the
// non-maximum suppression. Buffers are kept between calls: no allocation per frame once
// the largest ROI has been seen. Not thread-safe (one instance per thread).
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace aperture::perception {

class CannyEdgeDetector {
 public:
  // gray: CV_8UC1; roi inside gray (else std::invalid_argument naming both). Thresholds on the L1
  // Sobel magnitude, truncated to integers like cv::Canny (floor); low <= high. edges receives a
  // CV_8UC1 image of roi's size, 255 on edges (and, with dilate_3x3, on their 8 neighbours) and 0
  // elsewhere.
  void Detect(const cv::Mat& gray, const cv::Rect& roi, double low_threshold, double high_threshold,
              bool dilate_3x3, cv::Mat* edges);

 private:
  // Candidate test of padded index i: magnitude above low_ and a local maximum across the
  // gradient direction, with cv::Canny's sectors and comparisons.
  bool IsCandidate(int i) const;
  // Marks an unvisited candidate i as an edge and grows the edge through its 8-neighbourhood.
  void Grow(int i);

  int width_ = 0;   // ROI size
  int height_ = 0;
  int stride_ = 0;  // width_ + 2: buffers below are padded by one pixel on every side
  int low_ = 0;
  int high_ = 0;
  std::vector<int16_t> dx_, dy_, magnitude_;  // padded; magnitude_ 0 on the padding
  // 0 = not visited, 1 = visited and not an edge, 2 = edge; 1 on the padding.
  std::vector<uint8_t> state_;
  std::vector<int> stack_;
  std::vector<int> edge_indices_;  // padded indices of this call's edges
  std::vector<uint8_t> output_;    // padded edge image
};

}  // namespace aperture::perception
