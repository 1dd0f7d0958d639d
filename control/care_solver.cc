#include "control/care_solver.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "control/require.h"

namespace aperture::control {
namespace {

void RequireSymmetric(const Eigen::MatrixXd& M, const char* name) {
  const double scale = 1.0 + M.norm();
  if ((M - M.transpose()).norm() > 1e-10 * scale) {
    throw std::invalid_argument(std::string("CARE: matrix ") + name +
                                " must be symmetric; symmetrize it (0.5 (M + M^T))");
  }
}

struct Residual {
  double absolute = 0.0;
  double relative = 0.0;
};

// Frobenius residual of the CARE and its size relative to the terms that cancel.
Residual ComputeResidual(const Eigen::MatrixXd& A, const Eigen::MatrixXd& G,
                         const Eigen::MatrixXd& Q, const Eigen::MatrixXd& P) {
  const Eigen::MatrixXd AtP = A.transpose() * P;
  const Eigen::MatrixXd PGP = P * G * P;
  Residual r;
  r.absolute = (AtP + AtP.transpose() - PGP + Q).norm();
  const double scale = 2.0 * AtP.norm() + PGP.norm() + Q.norm();
  r.relative = scale > 0.0 ? r.absolute / scale : r.absolute;
  return r;
}

double MaxRealEigenvalue(const Eigen::MatrixXd& M) {
  const Eigen::VectorXcd eigenvalues = Eigen::EigenSolver<Eigen::MatrixXd>(M, false).eigenvalues();
  return eigenvalues.real().maxCoeff();
}

}  // namespace

std::string ToString(CareStatus status) {
  switch (status) {
    case CareStatus::kConverged:
      return "converged";
    case CareStatus::kNoStabilizingSolution:
      return "no stabilizing solution";
    case CareStatus::kMaxIterationsReached:
      return "max iterations reached";
  }
  return "unknown";
}

std::ostream& operator<<(std::ostream& os, const CareResult& result) {
  return os << "CARE " << ToString(result.status) << ": residual " << result.residual
            << " (relative " << result.relative_residual << "), max Re eig(A-BK) "
            << result.max_closed_loop_real_part << ", sign iterations " << result.sign_iterations
            << ", refinement iterations " << result.refinement_iterations << ", "
            << result.solve_time_s * 1e6 << " us";
}

std::optional<Eigen::MatrixXd> SolveContinuousLyapunov(const Eigen::MatrixXd& A,
                                                       const Eigen::MatrixXd& C) {
  const Eigen::Index n = A.rows();
  if (A.cols() != n || C.rows() != n || C.cols() != n) {
    throw std::invalid_argument("Lyapunov: A and C must be square of equal size");
  }
  RequireFinite(A, "CARE matrix A");
  RequireFinite(C, "CARE matrix C");
  // A = U T U^H with T upper triangular; A^T = A^H since A is real, so A^T X + X A + C = 0
  // becomes T^H Y + Y T = F with Y = U^H X U, F = -U^H C U, solved entry by entry.
  const Eigen::ComplexSchur<Eigen::MatrixXd> schur(A);
  const Eigen::MatrixXcd& T = schur.matrixT();
  const Eigen::MatrixXcd& U = schur.matrixU();
  const Eigen::MatrixXcd F = -(U.adjoint() * C.cast<std::complex<double>>() * U);
  Eigen::MatrixXcd Y(n, n);
  const double tiny = std::numeric_limits<double>::epsilon() * (1.0 + T.norm());
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      std::complex<double> rhs = F(i, j);
      for (Eigen::Index k = 0; k < i; ++k) rhs -= std::conj(T(k, i)) * Y(k, j);
      for (Eigen::Index k = 0; k < j; ++k) rhs -= Y(i, k) * T(k, j);
      const std::complex<double> diagonal = std::conj(T(i, i)) + T(j, j);
      if (std::abs(diagonal) <= tiny) return std::nullopt;
      Y(i, j) = rhs / diagonal;
    }
  }
  const Eigen::MatrixXd X = (U * Y * U.adjoint()).real();
  return Eigen::MatrixXd(0.5 * (X + X.transpose()));
}

CareResult SolveContinuousAlgebraicRiccati(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                           const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R,
                                           const CareOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  auto seconds_since_start = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const Eigen::Index n = A.rows();
  const Eigen::Index m = B.cols();
  if (n == 0 || A.cols() != n) throw std::invalid_argument("CARE: A must be square and non-empty");
  if (B.rows() != n || m == 0) {
    throw std::invalid_argument("CARE: B must have as many rows as A (" + std::to_string(n) +
                                ") and at least one column");
  }
  if (Q.rows() != n || Q.cols() != n) {
    throw std::invalid_argument("CARE: Q must be " + std::to_string(n) + " x " + std::to_string(n));
  }
  if (R.rows() != m || R.cols() != m) {
    throw std::invalid_argument("CARE: R must be " + std::to_string(m) + " x " + std::to_string(m));
  }
  RequireFinite(A, "CARE matrix A");
  RequireFinite(B, "CARE matrix B");
  RequireFinite(Q, "CARE matrix Q");
  RequireFinite(R, "CARE matrix R");
  RequireSymmetric(Q, "Q");
  RequireSymmetric(R, "R");
  const Eigen::LLT<Eigen::MatrixXd> R_llt(R);
  if (R_llt.info() != Eigen::Success) {
    throw std::invalid_argument(
        "CARE: R must be positive definite (give every input a weight > 0)");
  }
  if (Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Q, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .minCoeff() < -1e-12 * (1.0 + Q.norm())) {
    throw std::invalid_argument("CARE: Q must be positive semi-definite (state weights >= 0)");
  }

  CareResult result;
  const Eigen::MatrixXd RinvBt = R_llt.solve(B.transpose());
  const Eigen::MatrixXd G = B * RinvBt;

  // 1. Sign function of the Hamiltonian.
  Eigen::MatrixXd Z(2 * n, 2 * n);
  Z << A, -G, -Q, -A.transpose();
  bool sign_converged = false;
  for (int k = 0; k < options.max_sign_iterations; ++k) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(Z);
    const Eigen::VectorXd lu_diagonal = lu.matrixLU().diagonal().cwiseAbs();
    if (!(lu_diagonal.minCoeff() >
          std::numeric_limits<double>::epsilon() * lu_diagonal.maxCoeff())) {
      // Z singular: H has an eigenvalue at (or numerically on) the imaginary axis.
      result.sign_iterations = k;
      result.status = CareStatus::kNoStabilizingSolution;
      result.solve_time_s = seconds_since_start();
      return result;
    }
    // Determinant scaling c = |det Z|^(1/2n), computed in logs to avoid overflow.
    const double c = std::exp(lu_diagonal.array().log().sum() / static_cast<double>(2 * n));
    const Eigen::MatrixXd Z_next = 0.5 * (Z / c + c * lu.inverse());
    const double change = (Z_next - Z).cwiseAbs().colwise().sum().maxCoeff();
    const double size = Z_next.cwiseAbs().colwise().sum().maxCoeff();
    Z = Z_next;
    result.sign_iterations = k + 1;
    if (!Z.allFinite()) break;
    if (change <= options.sign_tolerance * size) {
      sign_converged = true;
      break;
    }
  }
  if (!sign_converged) {
    result.status =
        Z.allFinite() ? CareStatus::kMaxIterationsReached : CareStatus::kNoStabilizingSolution;
    result.solve_time_s = seconds_since_start();
    return result;
  }
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd M(2 * n, n), N(2 * n, n);
  M << Z.topRightCorner(n, n), Z.bottomRightCorner(n, n) + I;
  N << -(Z.topLeftCorner(n, n) + I), -Z.bottomLeftCorner(n, n);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(M);
  if (qr.rank() < n) {
    // The stable subspace is not a graph over the first n coordinates.
    result.status = CareStatus::kNoStabilizingSolution;
    result.solve_time_s = seconds_since_start();
    return result;
  }
  Eigen::MatrixXd P = qr.solve(N);
  P = 0.5 * (P + P.transpose());
  Eigen::MatrixXd K = RinvBt * P;
  Residual residual = ComputeResidual(A, G, Q, P);

  // 2. Newton-Kleinman refinement. The iterates P_k decrease monotonically in exact arithmetic but
  // their residual need not, so run until P stops changing (round-off) and keep the best iterate.
  Eigen::MatrixXd P_k = P, K_k = K;
  for (int k = 0; k < options.max_refinement_iterations; ++k) {
    const Eigen::MatrixXd A_closed = A - B * K_k;
    const std::optional<Eigen::MatrixXd> P_next =
        SolveContinuousLyapunov(A_closed, Q + K_k.transpose() * R * K_k);
    if (!P_next || !P_next->allFinite()) break;
    const double change = (*P_next - P_k).norm();
    P_k = *P_next;
    K_k = RinvBt * P_k;
    const Residual next_residual = ComputeResidual(A, G, Q, P_k);
    if (next_residual.absolute < residual.absolute) {
      P = P_k;
      K = K_k;
      residual = next_residual;
      result.refinement_iterations = k + 1;
    }
    if (change <= 1e-14 * P_k.norm()) break;
  }
  result.P = P;
  result.K = K;
  result.residual = residual.absolute;
  result.relative_residual = residual.relative;
  result.max_closed_loop_real_part = MaxRealEigenvalue(A - B * K);
  // A stabilizing solution needs a Hurwitz closed loop; a relative residual far above round-off
  // means the sign function met eigenvalues too close to the imaginary axis to separate.
  result.status = (result.max_closed_loop_real_part < 0.0 && residual.relative < 1e-8)
                      ? CareStatus::kConverged
                      : CareStatus::kNoStabilizingSolution;
  result.solve_time_s = seconds_since_start();
  return result;
}

}  // namespace aperture::control
