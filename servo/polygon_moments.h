#pragma once
// Geometric moments m_pq = integral over the polygon of x^p y^q dx dy, p + q <= 3, in closed form
// by Green's theorem (C. Steger, "On the calculation of arbitrary moments of polygons", TU
// Muenchen FGBV-96-05, 1996): with a_k = x_k y_k+1 - x_k+1 y_k over the edges,
//   m_pq = 1 / ((p+q+2)(p+q+1) C(p+q, p)) sum_k a_k sum_i sum_j C(i+j, i) C(p+q-i-j, p-i)
//          x_k^i x_k+1^(p-i) y_k^j y_k+1^(q-j).
// O(n) with a small constant; the moment servo hands these to ViSP (vpMomentObject::set)
// instead of vpMomentObject::fromVector, whose per-vertex cost is several times higher.
// The moments are those of the enclosed area whatever the vertex order (m00 > 0).
#include <Eigen/Core>
#include <vector>

namespace aperture::servo {

// m(p, q) for p + q <= 3; entries with p + q > 3 are 0. Vertices in order around the contour
// (either direction, not repeated at the end), at least 3.
Eigen::Matrix4d PolygonMoments(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace aperture::servo
