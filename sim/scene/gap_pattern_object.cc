#include "sim/scene/gap_pattern_object.h"

#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace aperture::sim {

SceneObject MakeGapPatternObject(const perception::GapPattern& pattern,
                                 const Eigen::Vector2d& panel_size_m, const Eigen::Isometry3d& T_WG,
                                 const std::string& name) {
  pattern.ValidatePattern("MakeGapPatternObject pattern");
  if (!(panel_size_m.x() > pattern.outer_size_m.x() && panel_size_m.y() > pattern.outer_size_m.y())) {
    std::ostringstream s;
    s << "MakeGapPatternObject: panel_size_m = (" << panel_size_m.transpose()
      << ") must exceed outer_size_m = (" << pattern.outer_size_m.transpose() << ") in both directions";
    throw std::invalid_argument(s.str());
  }
  constexpr double kTexel = 0.01;  // [m]
  constexpr int kWhite = 242;      // albedo 0.95
  constexpr int kBlack = 13;       // albedo 0.05
  const auto texels = [&](double m) { return static_cast<int>(std::lround(m / kTexel)); };
  cv::Mat image(texels(panel_size_m.y()), texels(panel_size_m.x()), CV_8UC3, cv::Scalar::all(kWhite));
  const auto band = [&](const Eigen::Vector2d& size) {
    return cv::Rect(texels((panel_size_m.x() - size.x()) / 2), texels((panel_size_m.y() - size.y()) / 2),
                    texels(size.x()), texels(size.y()));
  };
  image(band(pattern.outer_size_m)).setTo(cv::Scalar::all(kBlack));
  image(band(pattern.inner_size_m)).setTo(cv::Scalar::all(kWhite));
  const double hx = 0.5 * pattern.opening_size_m.x();
  const double hy = 0.5 * pattern.opening_size_m.y();
  Rectangle panel{panel_size_m, {{{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}}}, {}};
  Material material;
  material.texture = std::make_shared<Texture>(image, kTexel, Texture::Filter::kNearest, Texture::Wrap::kClamp);
  material.color = Rgb::Ones();
  return SceneObject(name, panel, material, T_WG);
}

bool GapPatternInView(const perception::CameraModel& camera, const perception::GapPattern& pattern,
                      const Eigen::Isometry3d& T_CG, const cv::Mat& object_id, int gap_object_id) {
  const Eigen::Vector2d half = 0.5 * 1.05 * pattern.outer_size_m;
  for (const Eigen::Vector2d& sign : {Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1),
                                      Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1)}) {
    const Eigen::Vector3d p_G(sign.x() * half.x(), sign.y() * half.y(), 0.0);
    Eigen::Vector2d px;
    if (!camera.Project(T_CG * p_G, &px) || !camera.IsInImage(px, 3.0)) return false;
    const int row = static_cast<int>(std::lround(px.y()));
    const int col = static_cast<int>(std::lround(px.x()));
    if (object_id.empty() || object_id.at<int>(row, col) != gap_object_id) return false;
  }
  return true;
}

}  // namespace aperture::sim
