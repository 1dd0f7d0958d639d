#include "control/so3.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <vector>

namespace aperture::control {
namespace {

// Perturbation E(delta) = (Exp(dr), dt) for delta = [dt; dr] (so3.h conventions) and back.
Eigen::Isometry3d Perturbation(const Vector6d& delta) {
  Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
  E.linear() = ExpSo3(delta.tail<3>());
  E.translation() = delta.head<3>();
  return E;
}

Vector6d PerturbationOf(const Eigen::Isometry3d& E) {
  Vector6d delta;
  delta << E.translation(), LogSo3(E.linear());
  return delta;
}

// Central differences of f at 0; step 1e-6 leaves errors ~1e-10 (truncation h^2 ~ 1e-12 times
// third derivatives of order 1, round-off 1e-16 / 1e-6).
template <int M, int N>
Eigen::Matrix<double, M, N> NumericJacobian(
    const std::function<Eigen::Matrix<double, M, 1>(const Eigen::Matrix<double, N, 1>&)>& f) {
  constexpr double kStep = 1e-6;
  Eigen::Matrix<double, M, N> J;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N, 1> d = Eigen::Matrix<double, N, 1>::Zero();
    d[i] = kStep;
    J.col(i) = (f(d) - f(-d)) / (2.0 * kStep);
  }
  return J;
}

Eigen::Vector3d RandomRotationVector(std::mt19937& rng, double max_angle) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, max_angle);
  return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized() * uniform(rng);
}

Eigen::Matrix3d SeriesExp(const Eigen::Matrix3d& A) {
  // sum_k A^k / k!, converges to round-off within 40 terms for |A| < 4.
  Eigen::Matrix3d sum = Eigen::Matrix3d::Identity(), term = Eigen::Matrix3d::Identity();
  for (int k = 1; k < 40; ++k) {
    term = term * A / k;
    sum += term;
  }
  return sum;
}

TEST(So3Test, SkewIsTheCrossProductAndVeeInvertsIt) {
  const Eigen::Vector3d a(0.3, -1.2, 2.5), b(-0.7, 0.4, 1.1);
  EXPECT_TRUE((Skew(a) * b).isApprox(a.cross(b), 1e-15));
  EXPECT_TRUE((Skew(a) + Skew(a).transpose()).isZero(0.0));
  EXPECT_EQ(Vee(Skew(a)), a);
}

TEST(So3Test, ExpMatchesTheMatrixExponentialAndLogInvertsIt) {
  std::mt19937 rng(3);
  for (int n = 0; n < 200; ++n) {
    const Eigen::Vector3d phi = RandomRotationVector(rng, M_PI - 1e-3);
    const Eigen::Matrix3d R = ExpSo3(phi);
    EXPECT_LT((R - SeriesExp(Skew(phi))).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
    // log(exp(phi)) = phi for |phi| < pi; near pi the log loses digits as 1 / sin(angle).
    EXPECT_LT((LogSo3(R) - phi).norm(), 1e-9);
    // exp(log(R)) = R for every rotation.
    EXPECT_LT((ExpSo3(LogSo3(R)) - R).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(So3Test, AngleOfPiRoundTripsUpToTheAxisSign) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  const Eigen::Matrix3d R = ExpSo3(M_PI * axis);
  const Eigen::Vector3d phi = LogSo3(R);
  EXPECT_NEAR(phi.norm(), M_PI, 1e-9);
  EXPECT_NEAR(std::abs(phi.normalized().dot(axis)), 1.0, 1e-12);
  EXPECT_LT((ExpSo3(phi) - R).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(So3Test, SmallAnglesStayExact) {
  // Below 1e-12 rad Exp takes the first-order branch: I + [phi]x is orthonormal to O(|phi|^2).
  for (const double angle : {0.0, 1e-15, 3e-13, 2e-12, 1e-9}) {
    const Eigen::Vector3d phi = angle * Eigen::Vector3d(0.6, -0.8, 0.0);
    const Eigen::Matrix3d R = ExpSo3(phi);
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((LogSo3(R) - phi).norm(), 1e-15 + 1e-6 * angle);
    EXPECT_LT((LogQuaternion(ExpQuaternion(phi)) - phi).norm(), 1e-15 + 1e-6 * angle);
    EXPECT_LT((LeftJacobianSo3(phi) - (Eigen::Matrix3d::Identity() + 0.5 * Skew(phi)))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-15);
  }
}

TEST(So3Test, QuaternionMapsAgreeWithTheMatrixMaps) {
  std::mt19937 rng(4);
  for (int n = 0; n < 100; ++n) {
    const Eigen::Vector3d phi = RandomRotationVector(rng, M_PI - 1e-3);
    const Eigen::Quaterniond q = ExpQuaternion(phi);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    EXPECT_LT((q.toRotationMatrix() - ExpSo3(phi)).cwiseAbs().maxCoeff(), 1e-14);
    // q and -q are one rotation: the log takes the shorter one.
    EXPECT_LT((LogQuaternion(q) - phi).norm(), 1e-9);
    EXPECT_LT((LogQuaternion(Eigen::Quaterniond(-q.coeffs())) - phi).norm(), 1e-9);
  }
}

TEST(So3Test, LeftAndRightJacobiansMatchNumericDerivatives) {
  std::mt19937 rng(5);
  for (int n = 0; n < 50; ++n) {
    const Eigen::Vector3d phi = RandomRotationVector(rng, 3.0);
    const Eigen::Matrix3d R = ExpSo3(phi);
    // Exp(phi + d) = Exp(J_l d) Exp(phi)  and  Exp(phi + d) = Exp(phi) Exp(J_r d), J_r = J_l(-phi).
    const Eigen::Matrix3d J_left = NumericJacobian<3, 3>(
        [&](const Eigen::Vector3d& d) { return LogSo3(ExpSo3(phi + d) * R.transpose()); });
    const Eigen::Matrix3d J_right = NumericJacobian<3, 3>(
        [&](const Eigen::Vector3d& d) { return LogSo3(R.transpose() * ExpSo3(phi + d)); });
    EXPECT_LT((J_left - LeftJacobianSo3(phi)).cwiseAbs().maxCoeff(), 1e-8);
    EXPECT_LT((J_right - LeftJacobianSo3(-phi)).cwiseAbs().maxCoeff(), 1e-8);
  }
}

TEST(Se3Test, ExpAndLogAreInversesAndMatchTheMatrixExponential) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int n = 0; n < 100; ++n) {
    Vector6d xi;
    for (int k = 0; k < 6; ++k) xi[k] = 2.0 * unit(rng);  // rotation angles up to 3.46 rad
    if (xi.tail<3>().norm() >= M_PI) continue;            // log returns angles in [0, pi]
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

Eigen::Isometry3d SomePose() {
  Eigen::Isometry3d T_AB = Eigen::Isometry3d::Identity();
  T_AB.linear() = ExpSo3(Eigen::Vector3d(0.3, -0.2, 0.5));
  T_AB.translation() = Eigen::Vector3d(0.4, -0.3, 2.0);
  return T_AB;
}

TEST(Se3Test, AdjointMovesARightPerturbationToTheLeft) {
  // T_AB E(delta_B) = E(Ad(T_AB) delta_B) T_AB to first order.
  const Eigen::Isometry3d T_AB = SomePose();
  const Matrix6d J = NumericJacobian<6, 6>([&](const Vector6d& delta_B) {
    return PerturbationOf(T_AB * Perturbation(delta_B) * T_AB.inverse());
  });
  EXPECT_LT((J - AdjointSe3(T_AB)).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(Se3Test, InversePoseCovarianceMatchesThePerturbedInverse) {
  // T_BA(delta_B) = (E(delta_A) T_AB)^-1 = E(delta_B) T_BA: delta_B = J delta_A, cov_B = J cov J^T.
  const Eigen::Isometry3d T_AB = SomePose();
  const Matrix6d J = NumericJacobian<6, 6>([&](const Vector6d& delta_A) {
    return PerturbationOf((Perturbation(delta_A) * T_AB).inverse() * T_AB);
  });
  Matrix6d covariance_AB = Matrix6d::Identity();
  covariance_AB(0, 4) = covariance_AB(4, 0) = 0.3;
  covariance_AB(2, 3) = covariance_AB(3, 2) = -0.2;
  EXPECT_LT((InversePoseCovariance(T_AB, covariance_AB) - J * covariance_AB * J.transpose())
                .cwiseAbs()
                .maxCoeff(),
            1e-7);
}


TEST(So3Test, MeanRotationIsTheGeodesicCentre) {
  const Eigen::Quaterniond centre = ExpQuaternion(Eigen::Vector3d(0.3, -1.2, 2.0));
  // Pairs symmetric about the centre (right perturbations +-phi): the mean is the centre exactly.
  std::vector<Eigen::Quaterniond> symmetric;
  for (const Eigen::Vector3d& phi :
       {Eigen::Vector3d(0.2, 0.0, 0.0), Eigen::Vector3d(0.0, 0.05, 0.1)}) {
    symmetric.push_back(centre * ExpQuaternion(phi));
    symmetric.push_back(centre * ExpQuaternion(-phi));
  }
  EXPECT_LT(MeanRotation(symmetric).angularDistance(centre), 1e-12);
  // Noisy copies (10 mrad per axis; q and -q mixed): the mean of 400 is ~sqrt(3)*10/20 mrad off.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 0.01);
  std::vector<Eigen::Quaterniond> noisy;
  for (int k = 0; k < 400; ++k) {
    const Eigen::Quaterniond q = centre * ExpQuaternion(Eigen::Vector3d(normal(rng), normal(rng),
                                                                       normal(rng)));
    noisy.push_back(k % 2 == 0 ? q : Eigen::Quaterniond(-q.coeffs()));
  }
  EXPECT_LT(MeanRotation(noisy).angularDistance(centre), 2.5e-3);
  EXPECT_GT(noisy.front().angularDistance(centre) + noisy.back().angularDistance(centre), 2.5e-3);
  EXPECT_THROW(MeanRotation({}), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
