#pragma once
// Exports of a TagMap (TagMap::Tags()):
//   YAML      origin_id and, per tag, family, id, size_m, T_WT as p_m [x, y, z] and q_xyzw, the
//             6x6 covariance of [p_WT [m]; rotation [rad]] row-major (36 numbers; absent for the
//             fixed origin), the pose before optimization, inlier/rejected observation counts.
//   top view  PNG looking down -z_W: metre grid, each tag as its square outline with x_T (red),
//             its id, and its ellipse_scale-sigma position ellipse in x-y (at least 1 px); the
//             pre-optimization position as a grey cross.
// Both throw std::runtime_error when the file cannot be written.
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "perception/tags/tag_map.h"

namespace aperture::perception {

void WriteTagMapYaml(const std::string& path, const std::vector<MappedTag>& tags,
                     const TagMapParams& params);

struct TopViewOptions {
  double pixels_per_m = 120.0;
  double margin_m = 0.5;
  double ellipse_scale = 3.0;  // sigmas
};
// The top view as an image (CV_8UC3); WriteTagMapTopView writes it as PNG.
cv::Mat DrawTagMapTopView(const std::vector<MappedTag>& tags, const TopViewOptions& options = {});
void WriteTagMapTopView(const std::string& path, const std::vector<MappedTag>& tags,
                        const TopViewOptions& options = {});

}  // namespace aperture::perception
