#include "servo/polygon_moments.h"

#include <gtest/gtest.h>
#include <visp3/core/vpMomentObject.h>
#include <visp3/core/vpPoint.h>

#include <cmath>
#include <random>
#include <vector>

namespace aperture::servo {
namespace {

TEST(PolygonMomentsTest, UnitSquareMatchesTheIntegrals) {
  // m_pq of [0, 1]^2 = 1 / ((p + 1)(q + 1)).
  const Eigen::Matrix4d m = PolygonMoments({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  for (int p = 0; p <= 3; ++p) {
    for (int q = 0; p + q <= 3; ++q) EXPECT_NEAR(m(p, q), 1.0 / ((p + 1) * (q + 1)), 1e-15);
  }
  EXPECT_EQ(m(2, 2), 0.0);  // beyond order 3
}

// Truth: ViSP's own vpMomentObject::fromVector on random star-shaped polygons, both vertex orders
// (ViSP wants them clockwise in the image; the closed form takes either).
TEST(PolygonMomentsTest, MatchesVispOnRandomPolygons) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int n = 0; n < 50; ++n) {
    const int count = 3 + static_cast<int>(unit(rng) * 40);
    std::vector<Eigen::Vector2d> polygon;
    const Eigen::Vector2d centre(unit(rng) - 0.5, unit(rng) - 0.5);
    for (int k = 0; k < count; ++k) {
      const double angle = 2.0 * M_PI * (k + 0.8 * unit(rng)) / count;
      const double radius = 0.05 + 0.4 * unit(rng);
      polygon.push_back(centre + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
    }
    // Counter-clockwise in x-y axes = clockwise in the image (y down): ViSP's order.
    std::vector<vpPoint> points(count);
    for (int k = 0; k < count; ++k) {
      points[k].set_x(polygon[k].x());
      points[k].set_y(polygon[k].y());
    }
    vpMomentObject object(3);
    object.setType(vpMomentObject::DENSE_POLYGON);
    object.fromVector(points);
    ASSERT_GT(object.get(0, 0), 0.0);
    const Eigen::Matrix4d m = PolygonMoments(polygon);
    const Eigen::Matrix4d reversed =
        PolygonMoments(std::vector<Eigen::Vector2d>(polygon.rbegin(), polygon.rend()));
    for (unsigned int p = 0; p <= 3; ++p) {
      for (unsigned int q = 0; p + q <= 3; ++q) {
        // Moments up to ~0.5 in size from sums of ~40 terms: 1e-14 absolute is rounding.
        EXPECT_NEAR(m(p, q), object.get(p, q), 1e-14) << "polygon " << n << " m" << p << q;
        EXPECT_NEAR(reversed(p, q), object.get(p, q), 1e-14);
      }
    }
  }
}

}  // namespace
}  // namespace aperture::servo
