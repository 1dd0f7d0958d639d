#include "control/care_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>
#include <stdexcept>

#include "control/lqr_body_rate_controller.h"
#include "control/vehicle_parameters.h"

namespace aperture::control {
namespace {

Eigen::MatrixXd Scalar(double v) { return Eigen::MatrixXd::Constant(1, 1, v); }

double MaxRealPart(const Eigen::MatrixXd& M) {
  return Eigen::EigenSolver<Eigen::MatrixXd>(M, false).eigenvalues().real().maxCoeff();
}

// 2 a P - P^2 b^2 / r + q = 0 -> P = r (a + sqrt(a^2 + b^2 q / r)) / b^2 (the root with
// a - b^2 P / r < 0).
TEST(CareSolver, MatchesScalarAnalyticSolution) {
  for (const double a : {-2.0, 0.0, 1.0, 5.0}) {
    const double b = 2.0, q = 3.0, r = 0.5;
    const CareResult result =
        SolveContinuousAlgebraicRiccati(Scalar(a), Scalar(b), Scalar(q), Scalar(r));
    ASSERT_TRUE(result.ok()) << result;
    const double expected = r * (a + std::sqrt(a * a + b * b * q / r)) / (b * b);
    // Round-off of a handful of flops on O(1) numbers.
    EXPECT_NEAR(result.P(0, 0), expected, 1e-12 * expected) << "a = " << a;
    EXPECT_NEAR(result.K(0, 0), b * expected / r, 1e-12 * b * expected / r);
    EXPECT_LT(result.max_closed_loop_real_part, 0.0);
  }
}

TEST(CareSolver, BodyRateSystemResidualAndGainStructure) {
  const VehicleParameters vehicle;
  const BodyRateLinearModel model = BuildBodyRateLinearModel(vehicle);
  const LqrBodyRateParameters params;
  const Eigen::MatrixXd Q = params.state_weights.asDiagonal();
  const Eigen::MatrixXd R = Eigen::MatrixXd::Identity(3, 3);
  const CareResult result = SolveContinuousAlgebraicRiccati(model.A, model.B, Q, R);
  ASSERT_TRUE(result.ok()) << result;
  EXPECT_LT(result.residual, 1e-9) << result;
  EXPECT_LT(result.relative_residual, 1e-12) << result;
  EXPECT_LT(MaxRealPart(model.A - model.B * result.K), 0.0);
  // Symmetric positive definite P.
  EXPECT_LT((result.P - result.P.transpose()).norm(), 1e-15 * result.P.norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(result.P).eigenvalues().minCoeff(), 0.0);
  // (G.11): rate i and torque i couple only with input i; analytic per-axis gains
  // k_omega = sqrt(q_omega), k_eta = sqrt(1 + 2 alpha k_omega / J) - 1 (header derivation).
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i == j) continue;
      EXPECT_NEAR(result.K(i, j), 0.0, 1e-12);
      EXPECT_NEAR(result.K(i, 3 + j), 0.0, 1e-12);
    }
    const double k_omega = std::sqrt(params.state_weights[i]);
    const double k_eta =
        std::sqrt(1.0 + 2.0 * model.time_constant_s * k_omega / vehicle.inertia_diag_kgm2[i]) - 1.0;
    EXPECT_NEAR(result.K(i, i), k_omega, 1e-10 * k_omega);
    EXPECT_NEAR(result.K(i, 3 + i), k_eta, 1e-10 * k_eta);
  }
}

// Random systems with generic (hence controllable) B and Q = I + L L^T / n: the stabilizing
// solution exists; A is often unstable. Single-input systems of order 8 are excluded: random ones
// are nearly uncontrollable, ||P|| reaches 1e3..1e6 and round-off alone puts the absolute residual
// above 1e-9 (the relative residual stays ~1e-13, see BodyRateSystem / the status check).
class CareRandomSystem : public ::testing::TestWithParam<int> {};

TEST_P(CareRandomSystem, ResidualHurwitzAndSymmetric) {
  std::mt19937 rng(1000 + GetParam());
  std::normal_distribution<double> normal;
  const int n = 2 + GetParam() % 7;
  const int m = 1 + GetParam() % 3 + (n > 4 ? 1 : 0);
  auto random = [&](int rows, int cols) {
    return Eigen::MatrixXd(Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return normal(rng); }));
  };
  // Spectral radius ~1 keeps ||P|| = O(1..10), so round-off in the residual is ~1e-14.
  const Eigen::MatrixXd A = random(n, n) / std::sqrt(static_cast<double>(n));
  const Eigen::MatrixXd B = random(n, m);
  const Eigen::MatrixXd L = random(n, n);
  const Eigen::MatrixXd Q = L * L.transpose() / n + Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd S = random(m, m);
  const Eigen::MatrixXd R = S * S.transpose() + Eigen::MatrixXd::Identity(m, m);
  const CareResult result = SolveContinuousAlgebraicRiccati(A, B, Q, R);
  ASSERT_TRUE(result.ok()) << result;
  EXPECT_LT(result.residual, 1e-9) << result << "\nP =\n" << result.P;
  EXPECT_LT(result.relative_residual, 1e-13) << result;
  EXPECT_LT(MaxRealPart(A - B * result.K), 0.0);
  EXPECT_LT((result.K - R.llt().solve(B.transpose() * result.P)).norm(), 1e-12 * result.K.norm());
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(result.P).eigenvalues().minCoeff(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Seeds, CareRandomSystem, ::testing::Range(0, 40));

TEST(CareSolver, ReportsUnstabilizableSystem) {
  // x_dot = x with no input: the unstable mode cannot be stabilized.
  const CareResult unstable =
      SolveContinuousAlgebraicRiccati(Scalar(1.0), Scalar(0.0), Scalar(1.0), Scalar(1.0));
  EXPECT_FALSE(unstable.ok()) << unstable;
  // Unweighted integrator with no input: eigenvalue 0 of H on the imaginary axis.
  const CareResult marginal =
      SolveContinuousAlgebraicRiccati(Scalar(0.0), Scalar(0.0), Scalar(0.0), Scalar(1.0));
  EXPECT_FALSE(marginal.ok()) << marginal;
}

TEST(CareSolver, RejectsMalformedInput) {
  const Eigen::MatrixXd I2 = Eigen::MatrixXd::Identity(2, 2);
  EXPECT_THROW(SolveContinuousAlgebraicRiccati(I2, I2, I2, -I2), std::invalid_argument);
  EXPECT_THROW(SolveContinuousAlgebraicRiccati(I2, I2, Scalar(1.0), I2), std::invalid_argument);
  Eigen::MatrixXd asymmetric = I2;
  asymmetric(0, 1) = 1.0;
  EXPECT_THROW(SolveContinuousAlgebraicRiccati(I2, I2, asymmetric, I2), std::invalid_argument);
  Eigen::MatrixXd nan = I2;
  nan(1, 1) = std::nan("");
  EXPECT_THROW(SolveContinuousAlgebraicRiccati(nan, I2, I2, I2), std::invalid_argument);
}

TEST(LyapunovSolver, SolvesRandomHurwitzEquation) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const int n = 6;
  Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return normal(rng); });
  A -= (MaxRealPart(A) + 1.0) * Eigen::MatrixXd::Identity(n, n);  // shift to Hurwitz
  const Eigen::MatrixXd L = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return normal(rng); });
  const Eigen::MatrixXd C = L * L.transpose();
  const auto X = SolveContinuousLyapunov(A, C);
  ASSERT_TRUE(X.has_value());
  EXPECT_LT((A.transpose() * *X + *X * A + C).norm(), 1e-10 * C.norm());
  // A singular equation (eigenvalues 1 and -1 pair up: 1 + (-1) = 0) is reported.
  EXPECT_FALSE(SolveContinuousLyapunov(Eigen::Vector2d(1.0, -1.0).asDiagonal().toDenseMatrix(),
                                       Eigen::MatrixXd::Identity(2, 2))
                   .has_value());
}

}  // namespace
}  // namespace aperture::control
