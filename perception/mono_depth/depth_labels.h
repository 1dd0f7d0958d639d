#pragma once
// Depth quantised into N labels whose width grows with depth (seed 003 Sec. III-A: "the covering
// range of depth values for label L_i from near to far is gradually increasing"): the edges are
// geometric between min_depth_m and max_depth_m, so every label spans the same ratio and the
// same error in ln(depth), the quantity Table I scores. A label stands for the geometric centre
// of its bin; depths outside [min, max] fall into the first / last label.
#include <vector>

namespace aperture::perception {

class DepthLabels {
 public:
  // Throws std::invalid_argument unless 0 < min_depth_m < max_depth_m and count >= 2.
  DepthLabels(double min_depth_m, double max_depth_m, int count);

  int Count() const { return static_cast<int>(edges_m_.size()) - 1; }
  double MinDepth() const { return edges_m_.front(); }
  double MaxDepth() const { return edges_m_.back(); }
  // Label of a depth [m]; NaN, +inf and depths beyond max go to the last (farthest) label.
  int LabelOf(double depth_m) const;
  // Geometric centre of label `label`'s bin [m].
  double DepthOf(int label) const;
  const std::vector<double>& Edges() const { return edges_m_; }

 private:
  std::vector<double> edges_m_;  // Count() + 1 increasing edges [m]
};

}  // namespace aperture::perception
