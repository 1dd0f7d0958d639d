#include "perception/mono_depth/depth_labels.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace aperture::perception {

DepthLabels::DepthLabels(double min_depth_m, double max_depth_m, int count) {
  if (!(min_depth_m > 0.0) || !(max_depth_m > min_depth_m) || !std::isfinite(max_depth_m) ||
      count < 2) {
    throw std::invalid_argument(
        "depth labels: need 0 < min_depth_m < max_depth_m (finite) and "
        "at least 2 labels; got min " +
        std::to_string(min_depth_m) + " m, max " + std::to_string(max_depth_m) + " m, " +
        std::to_string(count) + " labels");
  }
  const double ratio = std::log(max_depth_m / min_depth_m) / count;
  for (int i = 0; i <= count; ++i) edges_m_.push_back(min_depth_m * std::exp(ratio * i));
  edges_m_.back() = max_depth_m;
}

int DepthLabels::LabelOf(double depth_m) const {
  if (!(depth_m < edges_m_.back())) return Count() - 1;  // NaN, inf, far
  const auto it = std::upper_bound(edges_m_.begin() + 1, edges_m_.end() - 1, depth_m);
  return static_cast<int>(it - (edges_m_.begin() + 1));
}

double DepthLabels::DepthOf(int label) const {
  if (label < 0 || label >= Count()) {
    throw std::out_of_range("depth labels: label " + std::to_string(label) + " not in [0, " +
                            std::to_string(Count()) + ")");
  }
  return std::sqrt(edges_m_[label] * edges_m_[label + 1]);
}

}  // namespace aperture::perception
