#pragma once
// IMU-only attitude estimator of Faessler thesis paper B, Section B.2.5, (B.22)-(B.26): a
// quaternion prediction-update filter used while no vision estimate exists (launch by hand,
// recovery after a tracking loss).
//
//  * Prediction (B.22): zero-order quaternion integration of the bias-corrected gyro rate
//    omega_hat = omega_meas - b_omega held over the interval since the previous sample,
//        q_WB(k) = q_WB(k-1) (x) [cos(|w| dt / 2), w / |w| sin(|w| dt / 2)];
//    for |omega_hat| = 0 the estimate is kept.
//  * Update (B.23)-(B.26): the accelerometer is assumed to measure -g on average (specific force
//    f_B = R_WB^T g z_W), so the predicted "up" direction in B, z_pred_B = R_WB^T z_W, is rotated
//    towards f_B / |f_B| by the fraction k_corr of the angle beta between them:
//        beta = acos(z_pred_B . f_B / |f_B|),  h_B = f_B x z_pred_B / |...|,
//        q_corr = [cos(k_corr beta / 2), h_B sin(k_corr beta / 2)],  q_WB <- q_WB (x) q_corr.
//    The update only runs when |omega_hat| < 0.5 rad/s and ||f_B| - g| < 1.0 m/s^2 (B.26 text):
//    the accelerometer is trusted as a gravity sensor only then (a gate, not a continuously
//    weighted gain: the thesis uses a fixed k_corr).
//  * Initialization (B.26 text): the first sample that passes the gate sets roll and pitch from
//    the gravity direction (yaw 0, the smallest rotation taking f_B onto z_W). Reset() instead
//    starts from a given attitude.
//
// Roll and pitch are observable through gravity; yaw is integrated from the gyro only and drifts
// with the residual gyro bias. Biases (b_omega, b_acc) are constants from hover calibration,
// thesis (A.19), (A.22) (HoverCalibration); paper B does not estimate them on-line.
//
// beta = pi (estimate exactly upside-down relative to the measurement) leaves h_B of (B.24)
// undefined; any axis orthogonal to z_pred_B is then a shortest rotation, and z_pred_B's
// Eigen::unitOrthogonal() is used.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace aperture::control {

struct ImuAttitudeEstimatorParams {
  // k_corr of (B.25), < 1. The thesis gives no value; 0.01 per sample at 500 Hz is a tilt-error
  // time constant of 1 / (0.01 * 500) = 0.2 s while the gate is open, and it attenuates white
  // accelerometer direction noise by sqrt(k / (2 - k)) = 0.07.
  double correction_gain = 0.01;
  double max_update_rate_radps = 0.5;       // update gate on |omega_hat| (B.26 text)
  double max_accel_norm_error_mps2 = 1.0;   // update gate on ||f_B| - g| (B.26 text)
  double gravity_mps2 = 9.81;
  Eigen::Vector3d gyro_bias_B = Eigen::Vector3d::Zero();   // b_omega, (A.19) [rad/s]
  Eigen::Vector3d accel_bias_B = Eigen::Vector3d::Zero();  // b_acc, (A.22) [m/s^2]

  // Throws std::invalid_argument naming the field: correction_gain outside (0, 1], non-positive
  // gates or gravity, non-finite values.
  void Validate() const;
};

class ImuAttitudeEstimator {
 public:
  explicit ImuAttitudeEstimator(const ImuAttitudeEstimatorParams& params = {});

  // Starts from a known attitude (marks the estimate initialized); the next sample only sets the
  // time reference. Throws std::invalid_argument for a non-finite or zero quaternion.
  void Reset(const Eigen::Quaterniond& q_WB);

  // One IMU sample at t_s (strictly increasing, else std::invalid_argument naming t_s):
  // specific force f_B [m/s^2] and body rates omega_B [rad/s], both raw (biases are removed here).
  // Returns true when the accelerometer update (B.23)-(B.26) or the initialization used it.
  bool AddImu(double t_s, const Eigen::Vector3d& specific_force_B, const Eigen::Vector3d& omega_B);

  bool initialized() const { return initialized_; }
  // Attitude estimate R_WB (identity until initialized()).
  const Eigen::Quaterniond& q_WB() const { return q_WB_; }
  // Angle between the estimated z_B and z_W [rad].
  double TiltRad() const;
  // Z-Y-X Euler angles {roll, pitch, yaw} of q_WB [rad] (for logs; singular at |pitch| = pi/2).
  Eigen::Vector3d RollPitchYawRad() const;
  // Bias-corrected body rates of the last sample [rad/s].
  const Eigen::Vector3d& omega_B() const { return omega_hat_B_; }
  const ImuAttitudeEstimatorParams& params() const { return params_; }

 private:
  bool PassesUpdateGate(const Eigen::Vector3d& f_B, const Eigen::Vector3d& omega_hat_B) const;
  void Correct(const Eigen::Vector3d& f_B);

  ImuAttitudeEstimatorParams params_;
  Eigen::Quaterniond q_WB_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d omega_hat_B_ = Eigen::Vector3d::Zero();
  bool initialized_ = false;
  bool has_time_ = false;
  double last_t_s_ = 0.0;
};

}  // namespace aperture::control
