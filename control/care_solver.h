#pragma once
// Continuous algebraic Riccati equation (CARE)
//     A^T P + P A - P B R^{-1} B^T P + Q = 0,
// stabilizing solution P = P^T >= 0 and the LQR gain K = R^{-1} B^T P (u = -K x), used to design
// the body-rate LQR of the Faessler thesis (G.9)-(G.11).
//
// Method (Eigen only; Eigen has a real Schur decomposition but no eigenvalue reordering):
//  1. Stable invariant subspace of the Hamiltonian H = [A, -B R^{-1} B^T; -Q, -A^T] through the
//     matrix sign function (Newton iteration Z <- (Z/c + c Z^{-1})/2 with determinant scaling c,
//     Roberts 1971 / Byers 1987). With W = sign(H), [I; P] spans ker(W + I), so P is the
//     least-squares solution of [W12; W22 + I] P = -[W11 + I; W21]. Unlike an eigenvector basis of
//     H this stays well conditioned for repeated eigenvalues (the body-rate model has three equal
//     axes pairs).
//  2. Newton-Kleinman refinement (Kleinman 1968) started from the stabilizing gain of step 1:
//     solve the Lyapunov equation (A - BK)^T P + P (A - BK) = -(Q + K^T R K) by Bartels-Stewart on
//     the complex Schur form, K <- R^{-1} B^T P, until the residual stops decreasing. This brings
//     the residual to round-off level.
// Cost is O(n^3) per iteration; meant for the small systems of controller design (n <~ 50).
#include <Eigen/Core>
#include <optional>
#include <ostream>
#include <string>

namespace aperture::control {

struct CareOptions {
  // Sign-function iterations stop when ||Z_k+1 - Z_k||_1 <= tolerance * ||Z_k+1||_1. Quadratic
  // convergence makes 1e-12 cost only one extra iteration over 1e-6.
  double sign_tolerance = 1e-12;
  int max_sign_iterations = 100;
  // Newton-Kleinman refinement steps after the sign function (each halves the digits lost;
  // two or three reach round-off).
  int max_refinement_iterations = 10;
};

enum class CareStatus {
  kConverged,              // P is the stabilizing solution, A - BK is Hurwitz.
  kNoStabilizingSolution,  // H has eigenvalues on (or numerically at) the imaginary axis, or
                           // (A, B) is not stabilizable / (A, Q) has unobservable modes on it.
  kMaxIterationsReached,   // sign iteration did not converge within max_sign_iterations.
};

std::string ToString(CareStatus status);

struct CareResult {
  CareStatus status = CareStatus::kNoStabilizingSolution;
  Eigen::MatrixXd P;      // n x n, symmetric
  Eigen::MatrixXd K;      // m x n, K = R^{-1} B^T P
  double residual = 0.0;  // Frobenius norm of A^T P + P A - P B R^{-1} B^T P + Q
  // residual / (||A^T P|| + ||P A|| + ||P B R^{-1} B^T P|| + ||Q||) (Frobenius): the residual
  // relative to the size of the terms that cancel; ~1e-16 means solved to round-off.
  double relative_residual = 0.0;
  double max_closed_loop_real_part = 0.0;  // max Re(eig(A - BK)), < 0 when converged
  int sign_iterations = 0;
  int refinement_iterations = 0;
  double solve_time_s = 0.0;

  bool ok() const { return status == CareStatus::kConverged; }
};

std::ostream& operator<<(std::ostream& os, const CareResult& result);

// Solves the CARE for A (n x n), B (n x m), Q (n x n, symmetric positive semi-definite),
// R (m x m, symmetric positive definite). Throws std::invalid_argument naming the matrix when the
// dimensions do not match, an entry is not finite, Q or R is not symmetric, or R is not positive
// definite. An unsolvable but well-formed problem is reported through CareResult::status.
CareResult SolveContinuousAlgebraicRiccati(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                           const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R,
                                           const CareOptions& options = {});

// Solves the continuous Lyapunov equation A^T X + X A + C = 0 for Hurwitz A (Bartels-Stewart on
// the complex Schur form of A). Returns std::nullopt when lambda_i(A) + conj(lambda_j(A))
// (numerically) vanishes for some i, j, i.e. the equation is singular. Throws
// std::invalid_argument on dimension mismatch or non-finite entries.
std::optional<Eigen::MatrixXd> SolveContinuousLyapunov(const Eigen::MatrixXd& A,
                                                       const Eigen::MatrixXd& C);

}  // namespace aperture::control
