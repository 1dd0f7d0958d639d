#include "sim/scene/primitives.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/constants.h"
#include "control/require.h"

namespace aperture::sim {
namespace {

using control::kInf;
constexpr double kTwoPi = 6.283185307179586;

// Even-odd crossing test: true when p lies inside the simple polygon.
bool InsidePolygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  const size_t n = polygon.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

bool InsideEllipse(const EllipseHole& e, const Eigen::Vector2d& p) {
  const Eigen::Vector2d q = p - e.center_m;
  const double c = std::cos(e.angle_rad);
  const double s = std::sin(e.angle_rad);
  const double x = (c * q.x() + s * q.y()) / e.semi_axes_m.x();
  const double y = (-s * q.x() + c * q.y()) / e.semi_axes_m.y();
  return x * x + y * y <= 1.0;
}

bool IntersectRectangle(const Rectangle& r, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                        double t_min, double t_max, LocalHit* hit) {
  if (d.z() == 0.0) return false;
  const double t = -o.z() / d.z();
  if (!(t > t_min && t < t_max)) return false;
  const Eigen::Vector2d p(o.x() + t * d.x(), o.y() + t * d.y());
  const Eigen::Vector2d half = 0.5 * r.size_m;
  if (std::abs(p.x()) > half.x() || std::abs(p.y()) > half.y()) return false;
  for (const auto& polygon : r.polygon_holes) {
    if (InsidePolygon(polygon, p)) return false;
  }
  for (const auto& ellipse : r.ellipse_holes) {
    if (InsideEllipse(ellipse, p)) return false;
  }
  hit->t_m = t;
  hit->n_O = Eigen::Vector3d::UnitZ();
  hit->uv_m = p + half;
  return true;
}

bool IntersectBox(const Box& box, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min,
                  double t_max, LocalHit* hit) {
  // Slab method: entry = max of per-axis near planes, exit = min of far planes.
  double t_near = -kInf;
  double t_far = kInf;
  int near_axis = 0;
  int far_axis = 0;
  for (int a = 0; a < 3; ++a) {
    const double half = 0.5 * box.size_m[a];
    if (d[a] == 0.0) {
      if (std::abs(o[a]) > half) return false;
      continue;
    }
    double t0 = (-half - o[a]) / d[a];
    double t1 = (half - o[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_near) {
      t_near = t0;
      near_axis = a;
    }
    if (t1 < t_far) {
      t_far = t1;
      far_axis = a;
    }
  }
  if (t_near > t_far) return false;
  double t;
  int axis;
  if (t_near > t_min) {
    t = t_near;
    axis = near_axis;
  } else {
    t = t_far;  // origin inside the box: the exit face is the visible one
    axis = far_axis;
  }
  if (!(t > t_min && t < t_max)) return false;
  const Eigen::Vector3d p = o + t * d;
  hit->t_m = t;
  hit->n_O = Eigen::Vector3d::Zero();
  hit->n_O[axis] = p[axis] > 0.0 ? 1.0 : -1.0;
  const int a0 = axis == 0 ? 1 : 0;
  const int a1 = axis == 2 ? 1 : 2;
  hit->uv_m = Eigen::Vector2d(p[a0] + 0.5 * box.size_m[a0], p[a1] + 0.5 * box.size_m[a1]);
  return true;
}

double Azimuth(double x, double y) {
  const double phi = std::atan2(y, x);
  return phi < 0.0 ? phi + kTwoPi : phi;
}

bool IntersectCylinder(const Cylinder& c, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                       double t_min, double t_max, LocalHit* hit) {
  bool found = false;
  double best = t_max;
  const double r2 = c.radius_m * c.radius_m;
  const double a = d.x() * d.x() + d.y() * d.y();
  if (a > 0.0) {
    const double b = o.x() * d.x() + o.y() * d.y();  // half of the linear coefficient
    const double cc = o.x() * o.x() + o.y() * o.y() - r2;
    const double disc = b * b - a * cc;
    if (disc >= 0.0) {
      const double sq = std::sqrt(disc);
      for (const double t : {(-b - sq) / a, (-b + sq) / a}) {
        if (!(t > t_min && t < best)) continue;
        const double z = o.z() + t * d.z();
        if (z < 0.0 || z > c.height_m) continue;
        const double x = o.x() + t * d.x();
        const double y = o.y() + t * d.y();
        best = t;
        found = true;
        hit->t_m = t;
        hit->n_O = Eigen::Vector3d(x, y, 0.0) / c.radius_m;
        hit->uv_m = Eigen::Vector2d(c.radius_m * Azimuth(x, y), z);
        break;  // the smaller valid root is the nearer one
      }
    }
  }
  if (d.z() != 0.0) {
    for (const double z_cap : {0.0, c.height_m}) {
      const double t = (z_cap - o.z()) / d.z();
      if (!(t > t_min && t < best)) continue;
      const double x = o.x() + t * d.x();
      const double y = o.y() + t * d.y();
      if (x * x + y * y > r2) continue;
      best = t;
      found = true;
      hit->t_m = t;
      hit->n_O = Eigen::Vector3d(0.0, 0.0, z_cap > 0.0 ? 1.0 : -1.0);
      hit->uv_m = Eigen::Vector2d(x, y);
    }
  }
  return found;
}

bool IntersectSphere(const Sphere& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                     double t_min, double t_max, LocalHit* hit) {
  const double a = d.squaredNorm();
  const double b = o.dot(d);
  const double c = o.squaredNorm() - s.radius_m * s.radius_m;
  const double disc = b * b - a * c;
  if (disc < 0.0) return false;
  const double sq = std::sqrt(disc);
  for (const double t : {(-b - sq) / a, (-b + sq) / a}) {
    if (!(t > t_min && t < t_max)) continue;
    const Eigen::Vector3d p = o + t * d;
    hit->t_m = t;
    hit->n_O = p / s.radius_m;
    hit->uv_m = Eigen::Vector2d(s.radius_m * Azimuth(p.x(), p.y()),
                                s.radius_m * std::asin(std::clamp(hit->n_O.z(), -1.0, 1.0)));
    return true;
  }
  return false;
}

bool IntersectGround(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min, double t_max,
                     LocalHit* hit) {
  if (d.z() == 0.0) return false;
  const double t = -o.z() / d.z();
  if (!(t > t_min && t < t_max)) return false;
  hit->t_m = t;
  hit->n_O = Eigen::Vector3d::UnitZ();
  hit->uv_m = Eigen::Vector2d(o.x() + t * d.x(), o.y() + t * d.y());
  return true;
}

}  // namespace

bool IntersectPrimitive(const Primitive& primitive, const Eigen::Vector3d& o_O,
                        const Eigen::Vector3d& d_O, double t_min, double t_max, LocalHit* hit) {
  switch (primitive.index()) {
    case 0:
      return IntersectRectangle(*std::get_if<Rectangle>(&primitive), o_O, d_O, t_min, t_max, hit);
    case 1:
      return IntersectBox(*std::get_if<Box>(&primitive), o_O, d_O, t_min, t_max, hit);
    case 2:
      return IntersectCylinder(*std::get_if<Cylinder>(&primitive), o_O, d_O, t_min, t_max, hit);
    case 3:
      return IntersectSphere(*std::get_if<Sphere>(&primitive), o_O, d_O, t_min, t_max, hit);
    case 4:
      return IntersectGround(o_O, d_O, t_min, t_max, hit);
    default:
      return false;  // Led: drawn as a radiance blob, never hit
  }
}

double BoundingRadius(const Primitive& primitive) {
  if (const auto* r = std::get_if<Rectangle>(&primitive)) return 0.5 * r->size_m.norm();
  if (const auto* b = std::get_if<Box>(&primitive)) return 0.5 * b->size_m.norm();
  if (const auto* c = std::get_if<Cylinder>(&primitive)) {
    return std::hypot(c->radius_m, 0.5 * c->height_m);
  }
  if (const auto* s = std::get_if<Sphere>(&primitive)) return s->radius_m;
  if (const auto* l = std::get_if<Led>(&primitive)) return l->radius_m;
  return kInf;
}

Eigen::Vector3d BoundingCenter(const Primitive& primitive) {
  if (const auto* c = std::get_if<Cylinder>(&primitive)) {
    return Eigen::Vector3d(0.0, 0.0, 0.5 * c->height_m);
  }
  return Eigen::Vector3d::Zero();
}

void ValidatePrimitive(const Primitive& primitive) {
  if (const auto* r = std::get_if<Rectangle>(&primitive)) {
    control::RequirePositive(r->size_m.x(), "scene primitive Rectangle.size_m.x");
    control::RequirePositive(r->size_m.y(), "scene primitive Rectangle.size_m.y");
    for (const auto& polygon : r->polygon_holes) {
      if (polygon.size() < 3) {
        throw std::invalid_argument("scene primitive: Rectangle polygon hole has " +
                                    std::to_string(polygon.size()) +
                                    " vertices; a hole needs at least 3");
      }
    }
    for (const auto& e : r->ellipse_holes) {
      control::RequirePositive(e.semi_axes_m.x(), "scene primitive EllipseHole.semi_axes_m.x");
      control::RequirePositive(e.semi_axes_m.y(), "scene primitive EllipseHole.semi_axes_m.y");
    }
  } else if (const auto* b = std::get_if<Box>(&primitive)) {
    for (int a = 0; a < 3; ++a)
      control::RequirePositive(b->size_m[a], "scene primitive Box.size_m");
  } else if (const auto* c = std::get_if<Cylinder>(&primitive)) {
    control::RequirePositive(c->radius_m, "scene primitive Cylinder.radius_m");
    control::RequirePositive(c->height_m, "scene primitive Cylinder.height_m");
  } else if (const auto* s = std::get_if<Sphere>(&primitive)) {
    control::RequirePositive(s->radius_m, "scene primitive Sphere.radius_m");
  } else if (const auto* l = std::get_if<Led>(&primitive)) {
    control::RequirePositive(l->radius_m, "scene primitive Led.radius_m");
    control::RequirePositive(l->intensity, "scene primitive Led.intensity");
    control::RequireNonNegative(l->radiation_exponent, "scene primitive Led.radiation_exponent");
  }
}

}  // namespace aperture::sim
