#include "sim/scene/apriltag_object.h"

#include <memory>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "perception/tags/apriltag_family.h"

namespace aperture::sim {

cv::Mat MakeAprilTagImage(const std::string& family, int id) {
  const perception::AprilTagFamilyPtr fam = perception::CreateAprilTagFamily(family);
  if (id < 0 || id >= static_cast<int>(fam->ncodes)) {
    throw std::invalid_argument("AprilTag id " + std::to_string(id) + " outside family " + family +
                                " (ids 0.." + std::to_string(fam->ncodes - 1) + ")");
  }
  const int total = fam->total_width;
  cv::Mat image(total, total, CV_8UC1, cv::Scalar(0));
  // White ring just outside the black border (inside it for reversed-border families).
  const int white_border_width = fam->width_at_border + (fam->reversed_border ? 0 : 2);
  const int white_border_start = (total - white_border_width) / 2;
  cv::rectangle(
      image,
      cv::Rect(white_border_start, white_border_start, white_border_width, white_border_width),
      cv::Scalar(255), 1);
  // Data bits: most significant bit first, at (bit_x, bit_y) from the black border's corner.
  const int border_start = (total - fam->width_at_border) / 2;
  const uint64_t code = fam->codes[id];
  for (uint32_t i = 0; i < fam->nbits; ++i) {
    if (code & (uint64_t{1} << (fam->nbits - i - 1))) {
      image.at<uint8_t>(static_cast<int>(fam->bit_y[i]) + border_start,
                        static_cast<int>(fam->bit_x[i]) + border_start) = 255;
    }
  }
  return image;
}

double AprilTagPatternSize(const std::string& family, double tag_size_m) {
  const perception::AprilTagFamilyPtr fam = perception::CreateAprilTagFamily(family);
  return tag_size_m * fam->total_width / fam->width_at_border;
}

SceneObject MakeAprilTagObject(const std::string& family, int id, double tag_size_m,
                               const Eigen::Isometry3d& T_WO) {
  if (!(tag_size_m > 0.0)) {
    throw std::invalid_argument("MakeAprilTagObject: tag_size_m = " + std::to_string(tag_size_m) +
                                " must be > 0");
  }
  const cv::Mat bits = MakeAprilTagImage(family, id);
  cv::Mat rgb(bits.size(), CV_32FC3);
  for (int y = 0; y < bits.rows; ++y) {
    for (int x = 0; x < bits.cols; ++x) {
      const float albedo = bits.at<uint8_t>(y, x) ? 0.95f : 0.05f;
      rgb.at<cv::Vec3f>(y, x) = cv::Vec3f(albedo, albedo, albedo);
    }
  }
  const double pattern_m = AprilTagPatternSize(family, tag_size_m);
  SceneObject object;
  object.name = "tag" + std::to_string(id);
  object.primitive = Rectangle{Eigen::Vector2d(pattern_m, pattern_m), {}, {}};
  object.material.texture = std::make_shared<const Texture>(
      rgb, pattern_m / bits.cols, Texture::Filter::kNearest, Texture::Wrap::kClamp);
  object.material.color = Rgb::Ones();
  object.T_WO = T_WO;
  return object;
}

}  // namespace aperture::sim
