#include "perception/led/se3_twist.h"

#include <gtest/gtest.h>

#include <random>

namespace aperture::perception {
namespace {

TEST(Se3TwistTest, ExpAndLogAreInversesAndMatchTheMatrixExponential) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int n = 0; n < 100; ++n) {
    Vector6d xi;
    for (int k = 0; k < 6; ++k) xi[k] = 2.0 * unit(rng);  // rotation angles up to 3.46 rad
    if (xi.tail<3>().norm() >= M_PI) continue;              // log returns angles in [0, pi]
    EXPECT_LT((LogSe3(ExpSe3(xi)) - xi).cwiseAbs().maxCoeff(), 1e-9);
    // exp of the 4x4 twist matrix by its series: sum_k A^k / k! (converges fast for |A| < 4).
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A.topLeftCorner<3, 3>() = Skew(xi.tail<3>());
    A.topRightCorner<3, 1>() = xi.head<3>();
    Eigen::Matrix4d series = Eigen::Matrix4d::Identity(), term = Eigen::Matrix4d::Identity();
    for (int k = 1; k < 40; ++k) {
      term = term * A / k;
      series += term;
    }
    EXPECT_LT((ExpSe3(xi).matrix() - series).cwiseAbs().maxCoeff(), 1e-9);
  }
  // Small angles take the series branch of the left Jacobian.
  const Vector6d tiny = (Vector6d() << 0.1, -0.2, 0.3, 1e-10, -2e-10, 3e-10).finished();
  EXPECT_LT((LogSe3(ExpSe3(tiny)) - tiny).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace aperture::perception
