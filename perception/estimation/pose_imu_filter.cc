#include "perception/estimation/pose_imu_filter.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "control/require.h"
#include "control/so3.h"

namespace aperture::perception {
namespace {

using control::ExpQuaternion;
using control::LogQuaternion;
using control::Skew;
using Index = ErrorStateIndex;

void RequireUnitQuaternion(const Eigen::Quaterniond& q, const std::string& what) {
  control::RequireFinite(q.coeffs(), std::string("PoseImuFilter: ") + what);
  if (std::abs(q.norm() - 1.0) > 1e-6) {
    throw std::invalid_argument("PoseImuFilter: " + what + " has norm " + std::to_string(q.norm()) +
                                ", expected a unit quaternion; normalize it");
  }
}

template <int N>
void RequireCovariance(const Eigen::Matrix<double, N, N>& P, const std::string& what) {
  control::RequireFinite(P, std::string("PoseImuFilter: ") + what);
  const double scale = std::max(P.cwiseAbs().maxCoeff(), 1e-300);
  if ((P - P.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    throw std::invalid_argument("PoseImuFilter: " + what + " is not symmetric");
  }
  Eigen::LLT<Eigen::Matrix<double, N, N>> llt(P);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("PoseImuFilter: " + what +
                                " is not positive definite; give every component a variance > 0");
  }
}

}  // namespace

void PoseImuFilterParams::Validate() const {
  ValidateNoise("PoseImuFilterParams");
  control::RequireNonNegative(gravity_mps2, "PoseImuFilterParams.gravity_mps2");
  control::RequirePositive(initial_position_sigma_m,
                           "PoseImuFilterParams.initial_position_sigma_m");
  control::RequirePositive(initial_velocity_sigma_mps,
                           "PoseImuFilterParams.initial_velocity_sigma_mps");
  control::RequirePositive(initial_attitude_sigma_rad,
                           "PoseImuFilterParams.initial_attitude_sigma_rad");
  control::RequirePositive(initial_accel_bias_sigma_mps2,
                           "PoseImuFilterParams.initial_accel_bias_sigma_mps2");
  control::RequirePositive(initial_gyro_bias_sigma_radps,
                           "PoseImuFilterParams.initial_gyro_bias_sigma_radps");
  control::RequirePositive(history_duration_s, "PoseImuFilterParams.history_duration_s");
  for (const auto& [gate, name] : {std::pair{mahalanobis_gate, "mahalanobis_gate"},
                                   std::pair{height_mahalanobis_gate, "height_mahalanobis_gate"}}) {
    if (!(gate > 0.0)) {  // +inf allowed (no gating)
      throw std::invalid_argument(std::string("PoseImuFilterParams.") + name + " = " +
                                  std::to_string(gate) +
                                  " must be > 0 (+infinity disables gating)");
    }
  }
}

const char* ToString(PoseUpdateStatus status) {
  switch (status) {
    case PoseUpdateStatus::kApplied:
      return "applied";
    case PoseUpdateStatus::kRejectedOutlier:
      return "rejected_outlier";
    case PoseUpdateStatus::kTooOld:
      return "too_old";
    case PoseUpdateStatus::kAheadOfImu:
      return "ahead_of_imu";
  }
  return "unknown";
}

std::ostream& operator<<(std::ostream& os, const PoseUpdateResult& result) {
  return os << "PoseUpdateResult{status=" << ToString(result.status)
            << ", mahalanobis_sq=" << result.mahalanobis_sq << ", gate=" << result.gate
            << ", residual=[" << result.residual.transpose()
            << "], replayed_steps=" << result.replayed_steps << "}";
}

PoseImuEstimate InitialEstimate(const PoseImuFilterParams& params,
                                const control::QuadState& state) {
  params.Validate();
  PoseImuEstimate initial;
  initial.state = state;
  Vector15d sigma;
  sigma << Eigen::Vector3d::Constant(params.initial_position_sigma_m),
      Eigen::Vector3d::Constant(params.initial_velocity_sigma_mps),
      Eigen::Vector3d::Constant(params.initial_attitude_sigma_rad),
      Eigen::Vector3d::Constant(params.initial_accel_bias_sigma_mps2),
      Eigen::Vector3d::Constant(params.initial_gyro_bias_sigma_radps);
  initial.covariance = sigma.cwiseAbs2().asDiagonal();
  return initial;
}

PoseImuFilter::PoseImuFilter(const PoseImuFilterParams& params, const control::QuadState& initial)
    : PoseImuFilter(params, InitialEstimate(params, initial)) {}

PoseImuFilter::PoseImuFilter(const PoseImuFilterParams& params, const PoseImuEstimate& initial)
    : params_(params) {
  params_.Validate();
  control::RequireFinite(initial.state.t_s, "PoseImuFilter: initial state.t_s");
  control::RequireFinite(initial.state.p_WB, "PoseImuFilter: initial state.p_WB");
  control::RequireFinite(initial.state.v_W, "PoseImuFilter: initial state.v_W");
  RequireUnitQuaternion(initial.state.q_WB, "initial state.q_WB");
  control::RequireFinite(initial.accel_bias_B, "PoseImuFilter: initial accel_bias_B");
  control::RequireFinite(initial.gyro_bias_B, "PoseImuFilter: initial gyro_bias_B");
  RequireCovariance(initial.covariance, "initial covariance");

  Vector15d q = Vector15d::Zero();
  q.segment<3>(Index::kVelocity)
      .setConstant(params_.accel_noise_density * params_.accel_noise_density);
  q.segment<3>(Index::kAttitude)
      .setConstant(params_.gyro_noise_density * params_.gyro_noise_density);
  q.segment<3>(Index::kAccelBias)
      .setConstant(params_.accel_bias_random_walk * params_.accel_bias_random_walk);
  q.segment<3>(Index::kGyroBias)
      .setConstant(params_.gyro_bias_random_walk * params_.gyro_bias_random_walk);
  // G Q_c G^T: the noise enters dv as -R_WB n_a, whose covariance R sigma^2 I R^T = sigma^2 I
  // for an isotropic density, and dtheta as -n_g; so it is diagonal and constant.
  Q_c_ = q.asDiagonal();

  Entry entry;
  entry.t_s = initial.state.t_s;
  entry.x = Nominal{initial.state.p_WB, initial.state.v_W, initial.state.q_WB.normalized(),
                    initial.accel_bias_B, initial.gyro_bias_B};
  entry.P = initial.covariance;
  history_.push_back(entry);
}

void PoseImuFilter::PropagateBetween(const Entry& from, const Entry& to, Nominal* x,
                                     Matrix15d* P) const {
  const double dt = to.t_s - from.t_s;
  if (dt <= 0.0 || !(from.has_imu || to.has_imu)) return;
  // The first sample after construction is held constant back to the initial time.
  const ImuSample& begin = from.has_imu ? from.imu : to.imu;
  const ImuSample& end = to.has_imu ? to.imu : from.imu;
  const Eigen::Vector3d omega_begin = begin.omega_B - x->b_g;
  const Eigen::Vector3d omega_end = end.omega_B - x->b_g;
  const Eigen::Vector3d f_begin = begin.specific_force_B - x->b_a;
  const Eigen::Vector3d f_end = end.specific_force_B - x->b_a;
  const Eigen::Vector3d omega_mean = 0.5 * (omega_begin + omega_end);
  const Eigen::Vector3d f_mean = 0.5 * (f_begin + f_end);
  const Eigen::Vector3d gravity_W(0.0, 0.0, -params_.gravity_mps2);

  // Nominal state: rotation of the linearly varying rate (mean rate plus the second-order
  // coning term of the Magnus expansion), trapezoid on the acceleration.
  const Eigen::Matrix3d R_begin = x->q_WB.toRotationMatrix();
  const Eigen::Quaterniond q_end =
      (x->q_WB * ExpQuaternion(omega_mean * dt + omega_begin.cross(omega_end) * (dt * dt / 12.0)))
          .normalized();
  const Eigen::Matrix3d R_end = q_end.toRotationMatrix();
  const Eigen::Vector3d a_begin = R_begin * f_begin + gravity_W;
  const Eigen::Vector3d a_end = R_end * f_end + gravity_W;
  x->p_WB += x->v_W * dt + (2.0 * a_begin + a_end) * (dt * dt / 6.0);  // exact for linear a(t)
  x->v_W += 0.5 * (a_begin + a_end) * dt;
  x->q_WB = q_end;

  // Error-state dynamics A (linearized at the mid-interval rotation and mean inputs).
  const Eigen::Matrix3d R_mid = (R_begin * ExpQuaternion(0.5 * dt * omega_mean).toRotationMatrix());
  Matrix15d A = Matrix15d::Zero();
  A.block<3, 3>(Index::kPosition, Index::kVelocity).setIdentity();
  A.block<3, 3>(Index::kVelocity, Index::kAttitude) = -R_mid * Skew(f_mean);
  A.block<3, 3>(Index::kVelocity, Index::kAccelBias) = -R_mid;
  A.block<3, 3>(Index::kAttitude, Index::kAttitude) = -Skew(omega_mean);
  A.block<3, 3>(Index::kAttitude, Index::kGyroBias) = -Eigen::Matrix3d::Identity();

  const Matrix15d Adt = A * dt;
  const Matrix15d Adt2 = Adt * Adt;
  const Matrix15d Phi = Matrix15d::Identity() + Adt + 0.5 * Adt2 + Adt2 * Adt / 6.0;
  // Van Loan series (header); Q_c_ is diagonal so these products are cheap to write plainly.
  const Matrix15d Q_c = Q_c_ * process_noise_scale_;
  const Matrix15d AQ = A * Q_c;
  const Matrix15d AQAt = AQ * A.transpose();
  const Matrix15d A2Q = A * AQ;
  Matrix15d Q_d = Q_c * dt + (AQ + AQ.transpose()) * (0.5 * dt * dt) +
                  (A2Q + 2.0 * AQAt + A2Q.transpose()) * (dt * dt * dt / 6.0);
  *P = Phi * (*P) * Phi.transpose() + Q_d;
  *P = 0.5 * (*P + P->transpose());
}

void RequireProcessNoiseScale(double scale, const std::string& name) {
  control::Require(std::isfinite(scale) && scale >= 1.0, name, scale,
                   "must be finite and >= 1 (1: off)");
}

void PoseImuFilter::SetProcessNoiseScale(double scale) {
  RequireProcessNoiseScale(scale, "PoseImuFilter process noise scale");
  process_noise_scale_ = scale;
}

PoseUpdateResult PoseImuFilter::ApplyMeasurement(const PoseMeasurement& z, Nominal* x,
                                                 Matrix15d* P) const {
  const Eigen::Matrix3d R_WB = x->q_WB.toRotationMatrix();
  const Eigen::Matrix3d R_BX = z.q_BX.toRotationMatrix();
  const Eigen::Vector3d p_WX_pred = x->p_WB + R_WB * z.p_BX;
  const Eigen::Quaterniond q_WX_pred = x->q_WB * z.q_BX;
  Vector6d r;
  r.head<3>() = z.p_WX - p_WX_pred;
  r.tail<3>() = LogQuaternion(q_WX_pred.conjugate() * z.q_WX);

  Eigen::Matrix<double, 6, 15> H = Eigen::Matrix<double, 6, 15>::Zero();
  H.block<3, 3>(0, Index::kPosition).setIdentity();
  H.block<3, 3>(0, Index::kAttitude) = -R_WB * Skew(z.p_BX);
  H.block<3, 3>(3, Index::kAttitude) = R_BX.transpose();
  PoseUpdateResult result = ApplyLinearized<6>(r, H, z.covariance, params_.mahalanobis_gate, x, P);
  result.residual = r;
  return result;
}

PoseUpdateResult PoseImuFilter::ApplyMeasurement(const HeightMeasurement& z, Nominal* x,
                                                 Matrix15d* P) const {
  const Eigen::Matrix<double, 1, 1> r(z.z_W_m - x->p_WB.z());
  Eigen::Matrix<double, 1, 15> H = Eigen::Matrix<double, 1, 15>::Zero();
  H(0, Index::kPosition + 2) = 1.0;
  // The height corrects the vertical channel only (p_z, v_z, the accelerometer bias along z_B):
  // after an open-loop manoeuvre the filter's attitude-driven cross-covariances made a 6 cm
  // height residual move x by 10 cm and more (SITL recovery behind the gap). The Joseph form
  // keeps the covariance right for this suboptimal gain.
  Vector15d gain_mask = Vector15d::Zero();
  gain_mask(Index::kPosition + 2) = gain_mask(Index::kVelocity + 2) =
      gain_mask(Index::kAccelBias + 2) = 1.0;
  PoseUpdateResult result = ApplyLinearized<1>(r, H, Eigen::Matrix<double, 1, 1>(z.variance_m2),
                                               params_.height_mahalanobis_gate, x, P, gain_mask);
  result.residual(2) = r(0);
  return result;
}

template <int M>
PoseUpdateResult PoseImuFilter::ApplyLinearized(const Eigen::Matrix<double, M, 1>& r,
                                                const Eigen::Matrix<double, M, 15>& H,
                                                const Eigen::Matrix<double, M, M>& R, double gate,
                                                Nominal* x, Matrix15d* P,
                                                const Vector15d& gain_mask) const {
  PoseUpdateResult result;
  result.gate = gate;
  const Eigen::Matrix<double, 15, M> PHt = (*P) * H.transpose();
  const Eigen::Matrix<double, M, M> S = H * PHt + R;
  const Eigen::LDLT<Eigen::Matrix<double, M, M>> S_ldlt(S);
  result.mahalanobis_sq = r.dot(S_ldlt.solve(r));
  if (!(result.mahalanobis_sq <= gate)) {
    result.status = PoseUpdateStatus::kRejectedOutlier;
    return result;
  }
  const Eigen::Matrix<double, 15, M> K =
      gain_mask.asDiagonal() * S_ldlt.solve(PHt.transpose()).transpose();
  const Vector15d dx = K * r;
  const Matrix15d I_KH = Matrix15d::Identity() - K * H;
  *P = I_KH * (*P) * I_KH.transpose() + K * R * K.transpose();  // Joseph form

  const Eigen::Vector3d dtheta = dx.segment<3>(Index::kAttitude);
  x->p_WB += dx.segment<3>(Index::kPosition);
  x->v_W += dx.segment<3>(Index::kVelocity);
  x->q_WB = (x->q_WB * ExpQuaternion(dtheta)).normalized();
  x->b_a += dx.segment<3>(Index::kAccelBias);
  x->b_g += dx.segment<3>(Index::kGyroBias);
  // Covariance of the error about the corrected nominal: dtheta+ = dtheta - dtheta_hat, to first
  // order Jr(dtheta_hat)^-1 (dtheta - dtheta_hat) ~ (I - [dtheta_hat / 2]x) (...).
  Matrix15d G = Matrix15d::Identity();
  G.block<3, 3>(Index::kAttitude, Index::kAttitude) -= Skew(0.5 * dtheta);
  *P = G * (*P) * G.transpose();
  *P = 0.5 * (*P + P->transpose());
  result.status = PoseUpdateStatus::kApplied;
  return result;
}

void PoseImuFilter::Propagate(const ImuSample& sample) {
  control::RequireFinite(sample.t_s, "PoseImuFilter: ImuSample.t_s");
  control::RequireFinite(sample.specific_force_B, "PoseImuFilter: ImuSample.specific_force_B");
  control::RequireFinite(sample.omega_B, "PoseImuFilter: ImuSample.omega_B");
  Entry& last = history_.back();
  if (!last.has_imu && sample.t_s == last.t_s) {  // first sample exactly at the initial time
    last.has_imu = true;
    last.imu = sample;
    return;
  }
  if (!(sample.t_s > last.t_s)) {
    throw std::invalid_argument("PoseImuFilter: ImuSample.t_s = " + std::to_string(sample.t_s) +
                                " is not after the filter time " + std::to_string(last.t_s) +
                                "; IMU samples must arrive in increasing time order");
  }
  Entry entry;
  entry.t_s = sample.t_s;
  entry.has_imu = true;
  entry.imu = sample;
  entry.x = last.x;
  entry.P = last.P;
  PropagateBetween(last, entry, &entry.x, &entry.P);
  history_.push_back(entry);
  TrimHistory();
}

void PoseImuFilter::TrimHistory() {
  const double oldest_needed_s = history_.back().t_s - params_.history_duration_s;
  while (history_.size() > 1 && history_[1].t_s <= oldest_needed_s) history_.pop_front();
}

PoseUpdateResult PoseImuFilter::Update(const PoseMeasurement& z) {
  control::RequireFinite(z.t_s, "PoseImuFilter: PoseMeasurement.t_s");
  control::RequireFinite(z.p_WX, "PoseImuFilter: PoseMeasurement.p_WX");
  RequireUnitQuaternion(z.q_WX, "PoseMeasurement.q_WX");
  control::RequireFinite(z.p_BX, "PoseImuFilter: PoseMeasurement.p_BX");
  RequireUnitQuaternion(z.q_BX, "PoseMeasurement.q_BX");
  RequireCovariance(z.covariance, "PoseMeasurement.covariance");
  return Insert(z);
}

PoseUpdateResult PoseImuFilter::Update(const HeightMeasurement& z) {
  control::RequireFinite(z.t_s, "PoseImuFilter: HeightMeasurement.t_s");
  control::RequireFinite(z.z_W_m, "PoseImuFilter: HeightMeasurement.z_W_m");
  control::RequirePositive(z.variance_m2, "PoseImuFilter: HeightMeasurement.variance_m2");
  return Insert(z);
}

template <typename Measurement>
PoseUpdateResult PoseImuFilter::Insert(const Measurement& z) {
  PoseUpdateResult result;
  result.gate = std::is_same_v<Measurement, HeightMeasurement> ? params_.height_mahalanobis_gate
                                                               : params_.mahalanobis_gate;
  if (z.t_s > history_.back().t_s) {
    result.status = PoseUpdateStatus::kAheadOfImu;
    return result;
  }
  if (z.t_s < history_.front().t_s) {
    result.status = PoseUpdateStatus::kTooOld;
    return result;
  }
  // First entry after t_m; the one before it is the posterior we restart from.
  std::size_t next = 1;
  while (next < history_.size() && history_[next].t_s <= z.t_s) ++next;
  const Entry& before = history_[next - 1];

  Entry entry;
  entry.t_s = z.t_s;
  entry.measurement = z;
  if (next < history_.size() && before.has_imu) {
    const Entry& after = history_[next];
    const double alpha = (z.t_s - before.t_s) / (after.t_s - before.t_s);
    entry.has_imu = true;
    entry.imu.t_s = z.t_s;
    entry.imu.specific_force_B =
        (1.0 - alpha) * before.imu.specific_force_B + alpha * after.imu.specific_force_B;
    entry.imu.omega_B = (1.0 - alpha) * before.imu.omega_B + alpha * after.imu.omega_B;
  } else if (before.has_imu) {
    entry.has_imu = true;  // t_m is the time of `before`
    entry.imu = before.imu;
  } else if (next < history_.size()) {
    entry.has_imu = true;  // the first sample is held back to the initial time
    entry.imu = history_[next].imu;
    entry.imu.t_s = z.t_s;
  }
  entry.x = before.x;
  entry.P = before.P;
  PropagateBetween(before, entry, &entry.x, &entry.P);
  result = ApplyMeasurement(z, &entry.x, &entry.P);
  history_.insert(history_.begin() + static_cast<std::ptrdiff_t>(next), entry);

  // Re-propagate everything after t_m, re-applying later measurements.
  for (std::size_t k = next + 1; k < history_.size(); ++k) {
    Entry& current = history_[k];
    current.x = history_[k - 1].x;
    current.P = history_[k - 1].P;
    PropagateBetween(history_[k - 1], current, &current.x, &current.P);
    std::visit(
        [&](const auto& m) {
          if constexpr (!std::is_same_v<std::decay_t<decltype(m)>, std::monostate>) {
            ApplyMeasurement(m, &current.x, &current.P);
          }
        },
        current.measurement);
    ++result.replayed_steps;
  }
  return result;
}

PoseImuEstimate PoseImuFilter::Estimate() const {
  const Entry& last = history_.back();
  PoseImuEstimate estimate;
  estimate.state.t_s = last.t_s;
  estimate.state.p_WB = last.x.p_WB;
  estimate.state.v_W = last.x.v_W;
  estimate.state.q_WB = last.x.q_WB;
  estimate.state.omega_B =
      last.has_imu ? Eigen::Vector3d(last.imu.omega_B - last.x.b_g) : Eigen::Vector3d::Zero();
  estimate.accel_bias_B = last.x.b_a;
  estimate.gyro_bias_B = last.x.b_g;
  estimate.covariance = last.P;
  return estimate;
}

}  // namespace aperture::perception
