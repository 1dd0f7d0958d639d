#pragma once
// Pose + IMU error-state EKF (ESKF): fuses 6-DoF pose measurements (e.g. the gap or LED-target
// pose from a camera, Falanga et al. seed 000 Sec. III-A, which uses the multi-sensor fusion EKF
// of Lynen et al.) with a strap-down IMU (frame = B, DESIGN.md). Frames: W world (z up, gravity
// -z), B body = IMU, X the frame of the pose sensor with known extrinsics T_BX. Units SI.
//
// Nominal state x = {p_WB, v_W, q_WB, b_a (accelerometer bias, B), b_g (gyro bias, B)}.
// Error state (15-dim, this order): dx = [dp (W); dv (W); dtheta (B); db_a; db_g] with
//   p = p_hat + dp, v = v_hat + dv, b = b_hat + db,
//   R_WB = R_hat_WB * Exp(dtheta)       (local / right perturbation: dtheta is a rotation in B).
// IMU model (same as sim/sensors/imu_sensor.h, Kalibr / OpenVINS convention):
//   f_m = R_WB^T (a_W + g z_W) + b_a + n_a,   omega_m = omega_B + b_g + n_g,
//   b_a' = w_a,  b_g' = w_g,
// with continuous white-noise densities sigma_a, sigma_g [unit/sqrt(Hz)] and bias random walks
// sigma_ba, sigma_bg [unit/s/sqrt(Hz)] (PoseImuFilterParams).
//
// Propagation between consecutive IMU samples k, k+1 (dt = t_{k+1} - t_k): the inputs are taken
// as varying linearly between the samples, so the nominal state is integrated with the trapezoid
// rule (rotation by Exp of the mean rate, velocity by the mean of the accelerations at both
// ends, position with the matching second-order term). Error transition Phi = exp(A dt) by its
// third-order series (|A dt| <~ 1e-2 at 500 Hz, so the truncation is ~1e-9), process noise by
// the third-order series of Van Loan's integral
//   Q_d = int_0^dt exp(A s) G Q_c G^T exp(A s)^T ds ~= Q dt + (A Q + Q A^T) dt^2/2
//                                                      + (A^2 Q + 2 A Q A^T + Q A^T^2) dt^3/6,
// Q = G Q_c G^T, which gives e.g. the sigma_a^2 dt^3 / 3 position term exactly.
//
// Pose update: a measurement T_WX (position p_WX in W, rotation R_WX) of the frame X with
// extrinsics T_BX, predicted T_WX = T_WB T_BX. Residual r = [p_meas - p_pred;
// Log(R_pred^T R_meas)] with the measurement noise in the same convention: p_meas = p_WX + n_p
// (W), R_meas = R_WX Exp(n_theta) (n_theta in X), covariance 6x6 over [n_p; n_theta]. Jacobian
//   d r_p / d dp = I,  d r_p / d dtheta = -R_WB [p_BX]x,  d r_theta / d dtheta = R_BX^T.
// Gating: d^2 = r^T S^-1 r is compared with a chi-square(6) threshold; an outlier is reported
// and not applied. Update in Joseph form, then the error is injected into the nominal state and
// the covariance is reset with G = blkdiag(I, I, I - [dtheta/2]x, I, I) (Sola 2017, (287)).
//
// Height update (HeightMeasurement, e.g. a downward range sensor): the scalar residual
// z_W - p_WB.z with H = e_z^T on dp, gated by chi-square(1), the same Joseph-form update with a
// gain restricted to the vertical channel (p_z, v_z, b_a,z).
//
// Latency: the filter keeps a history of every IMU sample and applied pose measurement with the
// posterior at its time, covering the last history_duration_s (bounded, oldest dropped as new IMU
// samples arrive). A measurement stamped t_m in the past is inserted at t_m (the IMU input there
// is interpolated linearly between the neighbouring samples), the filter is restored to the
// history entry before t_m, updated at t_m and re-propagated through every later IMU sample,
// re-applying (and re-gating) later pose measurements. Measurements older than the history or
// newer than the latest IMU sample are not applied (status kTooOld / kAheadOfImu): feed the IMU
// first.
//
// Failures: non-finite inputs, non-increasing IMU stamps, non-positive-definite covariances and
// invalid parameters throw std::invalid_argument naming the input.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <deque>
#include <iosfwd>
#include <string>
#include <variant>

#include "control/quad_state.h"
#include "perception/imu_noise_params.h"
#include "perception/sensor_data.h"

namespace aperture::perception {

using Matrix15d = Eigen::Matrix<double, 15, 15>;
using Vector15d = Eigen::Matrix<double, 15, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

// Offsets of the blocks of the 15-dim error state.
struct ErrorStateIndex {
  static constexpr int kPosition = 0;   // dp in W [m]
  static constexpr int kVelocity = 3;   // dv in W [m/s]
  static constexpr int kAttitude = 6;   // dtheta in B [rad], R = R_hat Exp(dtheta)
  static constexpr int kAccelBias = 9;  // db_a in B [m/s^2]
  static constexpr int kGyroBias = 12;  // db_g in B [rad/s]
};

// IMU noise (accel/gyro noise densities, bias random walks): perception::ImuNoiseParams, whose
// defaults are the simulated IMU's (sim::ImuSensorParams derives from it too).
struct PoseImuFilterParams : ImuNoiseParams {
  double gravity_mps2 = 9.81;  // [m/s^2], along -z_W
  // Initial 1-sigma uncertainties used by the constructor that takes no covariance. Biases: a
  // MEMS accelerometer is within ~0.1 m/s^2 and a gyro within ~0.5 deg/s after start-up.
  double initial_position_sigma_m = 0.5;
  double initial_velocity_sigma_mps = 0.5;
  double initial_attitude_sigma_rad = 0.1;
  double initial_accel_bias_sigma_mps2 = 0.1;
  double initial_gyro_bias_sigma_radps = 0.01;
  // Span of the IMU / measurement history [s]: the largest latency a pose measurement may have.
  // 0.5 s covers camera pipelines (tens of ms) with a wide margin; replay cost grows linearly.
  double history_duration_s = 0.5;
  // chi-square(6) threshold on the Mahalanobis distance d^2 of a pose residual; 22.46 is the
  // 99.9 % quantile, so a consistent filter rejects 1 in 1000 inliers. +infinity disables gating.
  double mahalanobis_gate = 22.46;
  // chi-square(1) threshold of a height residual (HeightMeasurement); 10.83 is the 99.9 %
  // quantile. +infinity disables gating.
  double height_mahalanobis_gate = 10.83;

  // Throws std::invalid_argument naming the field: negative or non-finite densities, gravity,
  // sigmas <= 0, history_duration_s <= 0, gate <= 0 or NaN.
  void Validate() const;
};

// A measured pose of sensor frame X in W; see the header comment for the noise convention.
struct PoseMeasurement {
  double t_s = 0.0;                                // time the pose refers to, on the IMU clock [s]
  Eigen::Vector3d p_WX = Eigen::Vector3d::Zero();  // [m]
  Eigen::Quaterniond q_WX = Eigen::Quaterniond::Identity();  // rotation X -> W
  Matrix6d covariance = Matrix6d::Identity();                // over [n_p (W) m; n_theta (X) rad]
  Eigen::Vector3d p_BX = Eigen::Vector3d::Zero();            // extrinsics: origin of X in B [m]
  Eigen::Quaterniond q_BX = Eigen::Quaterniond::Identity();  // rotation X -> B
};

// A measured height of the body origin in W, e.g. from a downward range sensor at the body
// origin over a flat floor at z_floor_W: z_W = z_floor_W + range (z_B . z_W). Residual
// z_W - p_WB.z, Jacobian d r / d dp = e_z^T (the attitude enters only through the caller's
// projection of the range, a second-order term at the tilts a range sensor is used at).
struct HeightMeasurement {
  double t_s = 0.0;          // on the IMU clock [s]
  double z_W_m = 0.0;        // [m]
  double variance_m2 = 0.0;  // > 0 [m^2]
};

enum class PoseUpdateStatus {
  kApplied,          // fused
  kRejectedOutlier,  // d^2 above the gate, not fused
  kTooOld,           // older than the history, not fused
  kAheadOfImu,       // newer than the latest IMU sample, not fused
};
const char* ToString(PoseUpdateStatus status);

struct PoseUpdateResult {
  PoseUpdateStatus status = PoseUpdateStatus::kApplied;
  double mahalanobis_sq = 0.0;           // r^T S^-1 r (0 for kTooOld / kAheadOfImu)
  double gate = 0.0;                     // threshold it was compared with
  Vector6d residual = Vector6d::Zero();  // [m; rad] before the update (height: element 2 only)
  int replayed_steps = 0;                // history entries re-propagated after t_m
  bool applied() const { return status == PoseUpdateStatus::kApplied; }
};
std::ostream& operator<<(std::ostream& os, const PoseUpdateResult& result);

struct PoseImuEstimate {
  // t_s, p_WB, v_W, q_WB, and omega_B = latest gyro sample minus the gyro bias estimate.
  control::QuadState state;
  Eigen::Vector3d accel_bias_B = Eigen::Vector3d::Zero();  // [m/s^2]
  Eigen::Vector3d gyro_bias_B = Eigen::Vector3d::Zero();   // [rad/s]
  Matrix15d covariance = Matrix15d::Zero();  // of the error state, ErrorStateIndex order
};

// The estimate a filter starts from given only a state: `state` (t_s = filter time), zero biases
// and the diagonal covariance of the params' initial sigmas. Throws for invalid params.
PoseImuEstimate InitialEstimate(const PoseImuFilterParams& params, const control::QuadState& state);

// The one rule for a process-noise scale (SetProcessNoiseScale) or its adaptation's ceiling
// (PoseFusion::AdaptProcessNoise, the missions' max_process_noise_scale): finite and >= 1
// (1: off). Throws std::invalid_argument "<name> = <value> must be finite and >= 1 (1: off)".
void RequireProcessNoiseScale(double scale, const std::string& name);

class PoseImuFilter {
 public:
  // Starts at `initial` (state.t_s is the filter time; omega_B is ignored) with the diagonal
  // covariance of the params' initial sigmas, or with `initial_covariance` (15x15 symmetric
  // positive definite). Throws std::invalid_argument for invalid params, a non-finite or
  // non-unit-quaternion state or biases, or an invalid covariance.
  PoseImuFilter(const PoseImuFilterParams& params, const PoseImuEstimate& initial);
  PoseImuFilter(const PoseImuFilterParams& params, const control::QuadState& initial);

  // Propagates to sample.t_s, which must be later than the latest IMU sample (and not earlier
  // than the initial time). The first sample after construction is held constant back to the
  // initial time. Throws std::invalid_argument for non-finite fields or a non-increasing stamp.
  void Propagate(const ImuSample& sample);

  // Fuses a pose measurement at its time (see "Latency" above). Throws std::invalid_argument for
  // non-finite fields, non-unit quaternions or a covariance that is not symmetric positive
  // definite.
  PoseUpdateResult Update(const PoseMeasurement& measurement);
  // Fuses a height measurement the same way (history, latency, gate height_mahalanobis_gate).
  // Throws std::invalid_argument for non-finite fields or a variance that is not > 0.
  PoseUpdateResult Update(const HeightMeasurement& measurement);

  // Estimate at the latest IMU sample.
  PoseImuEstimate Estimate() const;
  double time_s() const { return history_.back().t_s; }
  // Multiplies the continuous process noise (every density and random walk) by `scale` (finite,
  // >= 1) from now on, re-propagations of the history included: an IMU noisier than its
  // specification (PoseFusion's innovation-matched adaptation). Throws std::invalid_argument.
  void SetProcessNoiseScale(double scale);
  double process_noise_scale() const { return process_noise_scale_; }
  // Number of entries held for re-propagation (bounded by history_duration_s times the IMU rate).
  std::size_t history_size() const { return history_.size(); }
  const PoseImuFilterParams& params() const { return params_; }

 private:
  struct Nominal {
    Eigen::Vector3d p_WB, v_W;
    Eigen::Quaterniond q_WB;
    Eigen::Vector3d b_a, b_g;
  };
  struct Entry {
    double t_s = 0.0;
    bool has_imu = false;  // false only for the initial entry until the first sample
    ImuSample imu;         // input at t_s (interpolated for measurement entries)
    std::variant<std::monostate, PoseMeasurement, HeightMeasurement> measurement;
    Nominal x;
    Matrix15d P;  // posterior at t_s
  };

  // Propagates `x`, `P` from entry `from` to the time and input of `to`.
  void PropagateBetween(const Entry& from, const Entry& to, Nominal* x, Matrix15d* P) const;
  PoseUpdateResult ApplyMeasurement(const PoseMeasurement& z, Nominal* x, Matrix15d* P) const;
  PoseUpdateResult ApplyMeasurement(const HeightMeasurement& z, Nominal* x, Matrix15d* P) const;
  // Gate and EKF update of an M-dim residual r = z - h(x) with Jacobian H and noise R, the
  // Kalman gain's rows multiplied by gain_mask (1: the error-state component is corrected, 0: it
  // is not); the result's status, d^2 and gate are set (not its residual).
  template <int M>
  PoseUpdateResult ApplyLinearized(const Eigen::Matrix<double, M, 1>& r,
                                   const Eigen::Matrix<double, M, 15>& H,
                                   const Eigen::Matrix<double, M, M>& R, double gate, Nominal* x,
                                   Matrix15d* P,
                                   const Vector15d& gain_mask = Vector15d::Ones()) const;
  // Inserts a validated measurement at its time and re-propagates the history after it.
  template <typename Measurement>
  PoseUpdateResult Insert(const Measurement& z);
  void TrimHistory();

  PoseImuFilterParams params_;
  Matrix15d Q_c_;                     // continuous noise G Q_c G^T in error-state coordinates
  double process_noise_scale_ = 1.0;  // multiplies Q_c_ (SetProcessNoiseScale)
  std::deque<Entry> history_;         // sorted by t_s; front() is the oldest kept posterior
};

}  // namespace aperture::perception
