#include "perception/estimation/pose_fusion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/so3.h"

namespace aperture::perception {
namespace {

// Rotations from calibration files carry ~1e-9 rounding; 1e-6 flags real mistakes (a scaled or
// sheared matrix, a reflection) without rejecting round-off.
constexpr double kRotationTolerance = 1e-6;

}  // namespace

void RequireRigid(const Eigen::Isometry3d& T, const std::string& name) {
  const Eigen::Matrix3d R = T.linear();
  if (!R.allFinite() || !T.translation().allFinite()) {
    throw std::invalid_argument(name + " must be finite");
  }
  const double orthonormality = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  if (orthonormality > kRotationTolerance || R.determinant() < 0.0) {
    throw std::invalid_argument(name +
                                " is not a rigid transform (rotation part not orthonormal "
                                "with determinant +1, |R^T R - I| = " +
                                std::to_string(orthonormality) + "): give a proper rotation");
  }
}

PoseMeasurement ToPoseMeasurement(const PoseObservation& observation, const PoseRig& rig) {
  const std::string what = "pose observation '" + observation.stream + "'";
  RequireRigid(rig.T_W_fixed, "PoseRig.T_W_fixed");
  RequireRigid(rig.T_B_moving, "PoseRig.T_B_moving");
  RequireRigid(observation.T_CX, what + " T_CX");
  if (!std::isfinite(observation.t_s)) throw std::invalid_argument(what + ": t_s must be finite");
  if (!observation.covariance_CX || !observation.covariance_CX->allFinite()) {
    throw std::invalid_argument(what + ": a finite covariance is needed to fuse it");
  }
  if (!std::isfinite(rig.covariance_scale) || rig.covariance_scale <= 0.0) {
    throw std::invalid_argument("PoseRig.covariance_scale must be > 0, got " +
                                std::to_string(rig.covariance_scale));
  }
  // T_WM: the measured frame M (the camera for a fixed target, the target for a fixed camera).
  Eigen::Isometry3d T_WM;
  Matrix6d J = Matrix6d::Zero();
  Matrix6d covariance;
  if (observation.fixed == PoseObservation::Fixed::kTarget) {
    const Eigen::Isometry3d T_XC = observation.T_CX.inverse();
    T_WM = rig.T_W_fixed * T_XC;
    covariance = control::InversePoseCovariance(observation.T_CX, *observation.covariance_CX);
    J.topLeftCorner<3, 3>() = rig.T_W_fixed.linear();
    J.topRightCorner<3, 3>() = -rig.T_W_fixed.linear() * control::Skew(T_XC.translation());
    J.bottomRightCorner<3, 3>() = T_XC.linear().transpose();  // R_CX
  } else {
    T_WM = rig.T_W_fixed * observation.T_CX;
    covariance = *observation.covariance_CX;
    J.topLeftCorner<3, 3>() = rig.T_W_fixed.linear();
    J.topRightCorner<3, 3>() =
        -rig.T_W_fixed.linear() * control::Skew(observation.T_CX.translation());
    J.bottomRightCorner<3, 3>() = observation.T_CX.linear().transpose();  // R_XC
  }
  PoseMeasurement z;
  z.t_s = observation.t_s;
  z.p_WX = T_WM.translation();
  z.q_WX = Eigen::Quaterniond(T_WM.linear()).normalized();
  z.covariance = rig.covariance_scale * J * covariance * J.transpose();
  z.covariance = 0.5 * (z.covariance + z.covariance.transpose()).eval();
  z.p_BX = rig.T_B_moving.translation();
  z.q_BX = Eigen::Quaterniond(rig.T_B_moving.linear()).normalized();
  return z;
}

PoseMeasurement InWorldFrame(const Eigen::Isometry3d& T_WO, const PoseMeasurement& z_O) {
  RequireRigid(T_WO, "InWorldFrame: T_WO");
  const Eigen::Matrix3d R_WO = T_WO.linear();
  PoseMeasurement z = z_O;
  z.p_WX = T_WO * z_O.p_WX;
  z.q_WX = (Eigen::Quaterniond(R_WO) * z_O.q_WX).normalized();
  Matrix6d J = Matrix6d::Identity();
  J.topLeftCorner<3, 3>() = R_WO;
  z.covariance = J * z_O.covariance * J.transpose();
  return z;
}

Eigen::Quaterniond BodyOrientation(const PoseMeasurement& z) {
  return (z.q_WX.normalized() * z.q_BX.normalized().conjugate()).normalized();
}

Eigen::Vector3d BodyPosition(const PoseMeasurement& z) {
  return z.p_WX - BodyOrientation(z) * z.p_BX;
}

void PoseFusionParams::Validate() const {
  filter.Validate();
  if (max_consecutive_rejections < 1) {
    throw std::invalid_argument("PoseFusionParams.max_consecutive_rejections must be >= 1, got " +
                                std::to_string(max_consecutive_rejections));
  }
  if (!(max_restart_rotation_rad > 0.0 && std::isfinite(max_restart_rotation_rad))) {
    throw std::invalid_argument(
        "PoseFusionParams.max_restart_rotation_rad must be finite and > 0 (pi: no limit), got " +
        std::to_string(max_restart_rotation_rad));
  }
}

PoseFusion::PoseFusion(const PoseFusionParams& params) : params_(params) { params_.Validate(); }

void PoseFusion::AddImu(const ImuSample& sample) {
  if (filter_ && sample.t_s > filter_->time_s()) filter_->Propagate(sample);
  imu_buffer_.push_back(sample);
  while (imu_buffer_.front().t_s < sample.t_s - params_.filter.history_duration_s) {
    imu_buffer_.pop_front();
  }
  if (filter_) ApplyPending();
}

std::vector<PoseFusionOutcome> PoseFusion::AddPose(const PoseMeasurement& measurement) {
  if (!filter_) {
    Restart(measurement);
    return {PoseFusionOutcome{measurement.t_s, true, {}}};
  }
  pending_.push_back(measurement);
  return ApplyPending();
}

void PoseFusion::AddHeight(const HeightMeasurement& measurement) {
  if (!std::isfinite(measurement.t_s) || !std::isfinite(measurement.z_W_m) ||
      !(measurement.variance_m2 > 0.0 && std::isfinite(measurement.variance_m2))) {
    throw std::invalid_argument(
        "HeightMeasurement (t_s, z_W_m, variance_m2) must be finite with variance_m2 > 0");
  }
  if (!filter_) return;
  pending_heights_.push_back(measurement);
  ApplyPending();
}

std::vector<PoseFusionOutcome> PoseFusion::ApplyPending() {
  while (!pending_heights_.empty() && pending_heights_.front().t_s <= filter_->time_s()) {
    if (filter_->Update(pending_heights_.front()).applied()) {
      ++counts_.heights_applied;
    } else {
      ++counts_.heights_rejected;
    }
    pending_heights_.pop_front();
  }
  std::vector<PoseFusionOutcome> outcomes;
  while (!pending_.empty() && pending_.front().t_s <= filter_->time_s()) {
    const PoseMeasurement z = pending_.front();
    pending_.pop_front();
    PoseFusionOutcome outcome;
    outcome.t_s = z.t_s;
    outcome.update = filter_->Update(z);
    AdaptToResidual(outcome.update);
    if (outcome.update.applied()) {
      ++counts_.applied;
      consecutive_rejections_ = 0;
      rejected_p_WB_.clear();
      last_pose_t_s_ = std::max(last_pose_t_s_, z.t_s);
    } else if (outcome.update.status == PoseUpdateStatus::kRejectedOutlier) {
      ++counts_.rejected_outlier;
      rejected_p_WB_.push_back(
          {z.t_s, BodyPosition(z), z.covariance.topLeftCorner<3, 3>().trace() / 3.0});
      if (++consecutive_rejections_ >= params_.max_consecutive_rejections) {
        if (filter_->Estimate().state.q_WB.angularDistance(BodyOrientation(z)) >
            params_.max_restart_rotation_rad) {
          ++counts_.restarts_refused;
          consecutive_rejections_ = 0;
          rejected_p_WB_.clear();
        } else {
          Restart(z);
          ++counts_.restarts;
          outcome.started_filter = true;
        }
      }
    } else {
      ++counts_.not_applied;
    }
    outcomes.push_back(outcome);
  }
  return outcomes;
}

void PoseFusion::Start(const control::QuadState& state) {
  StartAt(InitialEstimate(params_.filter, state));
}

void PoseFusion::Restart(const PoseMeasurement& z) {
  if (!z.p_WX.allFinite() || !z.q_WX.coeffs().allFinite() || !z.p_BX.allFinite() ||
      !z.q_BX.coeffs().allFinite() || !std::isfinite(z.t_s)) {
    throw std::invalid_argument("PoseMeasurement (t_s, p_WX, q_WX, p_BX, q_BX) must be finite");
  }
  control::QuadState state;
  state.t_s = z.t_s;
  state.q_WB = BodyOrientation(z);
  state.p_WB = BodyPosition(z);
  PoseImuEstimate initial = InitialEstimate(params_.filter, state);
  if (filter_) {  // restart: keep the biases, velocity from the rejected run of poses
    const PoseImuEstimate previous = filter_->Estimate();
    initial.accel_bias_B = previous.accel_bias_B;
    initial.gyro_bias_B = previous.gyro_bias_B;
    initial.state.v_W = previous.state.v_W;
    if (const std::optional<std::pair<Eigen::Vector3d, double>> fit = RejectedRunVelocity()) {
      const auto& [v_run_W, standard_error_mps] = *fit;
      if ((v_run_W - previous.state.v_W).norm() > 3.0 * standard_error_mps) {
        initial.state.v_W = v_run_W;
      }
    }
  }
  StartAt(initial);
  last_pose_t_s_ = z.t_s;
}

std::optional<std::pair<Eigen::Vector3d, double>> PoseFusion::RejectedRunVelocity() const {
  if (rejected_p_WB_.size() < 2) return std::nullopt;
  double t_mean = 0.0, variance_m2 = 0.0;
  Eigen::Vector3d p_mean = Eigen::Vector3d::Zero();
  for (const RejectedPosition& r : rejected_p_WB_) {
    t_mean += r.t_s;
    p_mean += r.p_WB;
    variance_m2 += r.variance_m2;
  }
  const double n = static_cast<double>(rejected_p_WB_.size());
  t_mean /= n;
  p_mean /= n;
  variance_m2 /= n;
  double s_tt = 0.0;
  Eigen::Vector3d s_tp = Eigen::Vector3d::Zero();
  for (const RejectedPosition& r : rejected_p_WB_) {
    s_tt += (r.t_s - t_mean) * (r.t_s - t_mean);
    s_tp += (r.t_s - t_mean) * (r.p_WB - p_mean);
  }
  if (!(s_tt > 0.0)) return std::nullopt;
  return std::make_pair(Eigen::Vector3d(s_tp / s_tt), std::sqrt(variance_m2 / s_tt));
}

void PoseFusion::Start(const PoseImuEstimate& initial) {
  if (!imu_buffer_.empty() &&
      initial.state.t_s < imu_buffer_.back().t_s - params_.filter.history_duration_s) {
    throw std::invalid_argument(
        "PoseFusion::Start: the initial estimate at t = " + std::to_string(initial.state.t_s) +
        " s is older than the buffered IMU (from " +
        std::to_string(imu_buffer_.back().t_s - params_.filter.history_duration_s) +
        " s); start from a later estimate or raise filter.history_duration_s");
  }
  StartAt(initial);
}

void PoseFusion::StartAt(const PoseImuEstimate& initial) {
  rejected_p_WB_.clear();
  consecutive_rejections_ = 0;
  filter_ = std::make_unique<PoseImuFilter>(params_.filter, initial);
  filter_->SetProcessNoiseScale(process_noise_scale_);
  for (const ImuSample& sample : imu_buffer_) {
    if (sample.t_s > filter_->time_s()) filter_->Propagate(sample);
  }
  ++counts_.starts;
}

void PoseFusion::AdaptProcessNoise(double max_scale) {
  RequireProcessNoiseScale(max_scale, "PoseFusion::AdaptProcessNoise max_scale");
  max_process_noise_scale_ = max_scale;
}

void PoseFusion::AdaptToResidual(const PoseUpdateResult& update) {
  if (max_process_noise_scale_ <= 1.0 || (update.status != PoseUpdateStatus::kApplied &&
                                          update.status != PoseUpdateStatus::kRejectedOutlier)) {
    return;
  }
  constexpr double kWeight = 1.0 / 20.0;  // running mean over ~20 measurements
  constexpr double kGain = 0.2;           // scale *= m^kGain per measurement
  constexpr double kDegreesOfFreedom = 6.0;
  const double normalized = std::min(update.mahalanobis_sq, update.gate) / kDegreesOfFreedom;
  mean_normalized_innovation_ += kWeight * (normalized - mean_normalized_innovation_);
  process_noise_scale_ =
      std::clamp(process_noise_scale_ * std::pow(mean_normalized_innovation_, kGain), 1.0,
                 max_process_noise_scale_);
  filter_->SetProcessNoiseScale(process_noise_scale_);
}

std::optional<PoseImuEstimate> PoseFusion::estimate() const {
  if (!filter_) return std::nullopt;
  return filter_->Estimate();
}

}  // namespace aperture::perception
