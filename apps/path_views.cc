#include "apps/path_views.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "output/svg_plot.h"

namespace aperture::apps {
namespace {

constexpr int kCirclePoints = 16;  // cylinders and spheres as 16-gons: < 2 % radius error

// Points on the surface of `primitive` (in O) whose projections' hull is the outline; none for
// shapes without extent (ground planes, LEDs).
std::vector<Eigen::Vector3d> OutlinePoints_O(const sim::Primitive& primitive) {
  std::vector<Eigen::Vector3d> points;
  if (const auto* rectangle = std::get_if<sim::Rectangle>(&primitive)) {
    const Eigen::Vector2d h = 0.5 * rectangle->size_m;
    for (const double sx : {-1.0, 1.0}) {
      for (const double sy : {-1.0, 1.0}) points.emplace_back(sx * h.x(), sy * h.y(), 0.0);
    }
  } else if (const auto* box = std::get_if<sim::Box>(&primitive)) {
    const Eigen::Vector3d h = 0.5 * box->size_m;
    for (int corner = 0; corner < 8; ++corner) {
      points.emplace_back((corner & 1 ? 1 : -1) * h.x(), (corner & 2 ? 1 : -1) * h.y(),
                          (corner & 4 ? 1 : -1) * h.z());
    }
  } else if (const auto* cylinder = std::get_if<sim::Cylinder>(&primitive)) {
    for (int k = 0; k < kCirclePoints; ++k) {
      const double a = 2.0 * M_PI * k / kCirclePoints;
      const Eigen::Vector2d xy = cylinder->radius_m * Eigen::Vector2d(std::cos(a), std::sin(a));
      points.emplace_back(xy.x(), xy.y(), 0.0);
      points.emplace_back(xy.x(), xy.y(), cylinder->height_m);
    }
  } else if (const auto* sphere = std::get_if<sim::Sphere>(&primitive)) {
    for (int k = 0; k < kCirclePoints; ++k) {  // three great circles cover every view axis
      const double a = 2.0 * M_PI * k / kCirclePoints;
      const double c = sphere->radius_m * std::cos(a), s = sphere->radius_m * std::sin(a);
      points.emplace_back(c, s, 0.0);
      points.emplace_back(c, 0.0, s);
      points.emplace_back(0.0, c, s);
    }
  }
  return points;
}

// One view: the path and every object's outline, outlines joined into one series broken by NaN
// (SvgPlot never draws through non-finite values).
std::string View(const std::string& title, const std::string& vertical_label, int vertical_axis,
                 const std::vector<control::QuadState>& trajectory, const sim::Scene& scene,
                 const std::vector<std::string>& skipped) {
  std::vector<double> path_x, path_v, outline_x, outline_v;
  for (const control::QuadState& state : trajectory) {
    path_x.push_back(state.p_WB.x());
    path_v.push_back(state.p_WB(vertical_axis));
  }
  for (const sim::SceneObject& object : scene.objects()) {
    if (std::find(skipped.begin(), skipped.end(), object.name) != skipped.end()) continue;
    std::vector<cv::Point2f> projected;
    for (const Eigen::Vector3d& p_O : OutlinePoints_O(object.primitive)) {
      const Eigen::Vector3d p_W = object.T_WO * p_O;
      projected.emplace_back(float(p_W.x()), float(p_W(vertical_axis)));
    }
    if (projected.empty()) continue;
    std::vector<cv::Point2f> hull;
    cv::convexHull(projected, hull);
    hull.push_back(hull.front());  // closed outline
    for (const cv::Point2f& p : hull) {
      outline_x.push_back(p.x);
      outline_v.push_back(p.y);
    }
    outline_x.push_back(std::numeric_limits<double>::quiet_NaN());
    outline_v.push_back(std::numeric_limits<double>::quiet_NaN());
  }
  output::SvgPlot plot({title, "x_W [m]", vertical_label});
  plot.AddLine("scene objects", outline_x, outline_v)
      .AddLine("path (ground truth)", path_x, path_v);
  if (!path_x.empty()) {  // a hover is a dot of a path: mark where it starts and ends
    plot.AddScatter("start, end", {path_x.front(), path_x.back()}, {path_v.front(), path_v.back()});
  }
  return plot.Render();
}

}  // namespace

void AddPathViews(const std::vector<control::QuadState>& trajectory, const sim::Scene& scene,
                  const std::vector<std::string>& skipped, output::HtmlReport* report) {
  report->AddSection("Path");
  report->AddSvg(View("Path seen from above", "y_W [m]", 1, trajectory, scene, skipped),
                 "Path seen from above: the vehicle's ground-truth position and the outlines of "
                 "the scene's objects");
  report->AddSvg(View("Path seen from the side", "z_W [m]", 2, trajectory, scene, skipped),
                 "Path seen from the side");
}

}  // namespace aperture::apps
