#include "control/imu_attitude_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "control/constants.h"

namespace aperture::control {
namespace {

constexpr double kImuRate_hz = 500.0;  // Hz, the thesis' IMU rate (B.2.5)
constexpr double kImuDt_s = 1.0 / kImuRate_hz;
// Per-sample white noise of a MEMS IMU at 500 Hz (a few times the sim's MPU-6000 densities).
constexpr double kAccelSigma = 0.05;  // m/s^2
constexpr double kGyroSigma = 0.002;  // rad/s

// Roll/pitch error: angle between the true and the estimated up direction in B (yaw-free).
double TiltError(const Eigen::Quaterniond& q_true, const Eigen::Quaterniond& q_est) {
  const Eigen::Vector3d up_true = q_true.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_est = q_est.conjugate() * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(up_true.dot(up_est), -1.0, 1.0));
}

// Kinematic IMU of a vehicle rotating at constant omega_B about its fixed centre (a = 0):
// specific force R^T (a + g z_W), gyro omega, Gaussian noise from a fixed seed.
class RotatingVehicle {
 public:
  RotatingVehicle(const Eigen::Quaterniond& q0, const Eigen::Vector3d& omega_B, unsigned seed)
      : q_WB_(q0), omega_B_(omega_B), rng_(seed) {}
  void Step() {
    t_ += kImuDt_s;
    const double angle = omega_B_.norm() * kImuDt_s;
    if (angle > 0.0) {
      q_WB_ = (q_WB_ * Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega_B_.normalized())))
                  .normalized();
    }
  }
  Eigen::Vector3d Accel() {
    return q_WB_.conjugate() * Eigen::Vector3d(0, 0, kGravity_mps2) + kAccelSigma * Noise();
  }
  Eigen::Vector3d Gyro() { return omega_B_ + kGyroSigma * Noise(); }
  void set_omega_B(const Eigen::Vector3d& omega_B) { omega_B_ = omega_B; }
  const Eigen::Quaterniond& q_WB() const { return q_WB_; }
  double t() const { return t_; }

 private:
  Eigen::Vector3d Noise() { return {normal_(rng_), normal_(rng_), normal_(rng_)}; }
  Eigen::Quaterniond q_WB_;
  Eigen::Vector3d omega_B_;
  double t_ = 0.0;
  std::mt19937 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

struct EstimatorRun {
  double convergence_time_s = -1.0;  // first time the tilt error is below 1 deg
  double steady_rms_rad = 0.0;
  double steady_max_rad = 0.0;
};

// Feeds the estimator for duration_s; steady-state statistics over the last steady_s.
EstimatorRun Feed(ImuAttitudeEstimator& estimator, RotatingVehicle& vehicle, double duration_s,
                  double steady_s) {
  EstimatorRun run;
  double sum_sq = 0.0;
  int n = 0;
  const int steps = static_cast<int>(std::lround(duration_s * kImuRate_hz));
  for (int k = 0; k < steps; ++k) {
    vehicle.Step();
    estimator.AddImu(vehicle.t(), vehicle.Accel(), vehicle.Gyro());
    const double e = TiltError(vehicle.q_WB(), estimator.q_WB());
    if (run.convergence_time_s < 0.0 && e < kPi / 180.0) run.convergence_time_s = vehicle.t();
    if (k >= steps - static_cast<int>(steady_s * kImuRate_hz)) {
      sum_sq += e * e;
      ++n;
      run.steady_max_rad = std::max(run.steady_max_rad, e);
    }
  }
  run.steady_rms_rad = std::sqrt(sum_sq / n);
  return run;
}

// Pure correction (B.25) shrinks the tilt error by (1 - k_corr) per sample: from pi to 1 deg in
// ln(180) / -ln(1 - k) samples.
double PredictedConvergenceTime(double k_corr) {
  return std::log(180.0) / -std::log(1.0 - k_corr) / kImuRate_hz;
}

// Steady-state tilt RMS from accelerometer direction noise (sigma_a / g per axis) through the
// first-order low pass x <- (1 - k) x + k n: per-axis std sigma sqrt(k / (2 - k)); the tilt is
// the norm of two such axes. Gyro noise adds sigma_g dt / sqrt(2k) = 3e-5 rad, negligible.
double PredictedSteadyRms(double k_corr) {
  return std::sqrt(2.0) * kAccelSigma / kGravity_mps2 * std::sqrt(k_corr / (2.0 - k_corr));
}

const Eigen::Quaterniond kTrueStart(Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-0.1, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
// Estimate exactly upside-down: rotated by 180 deg about a body axis orthogonal to the true up
// direction, so the estimated up is the antipode of the true one (the degenerate case of B.24).
Eigen::Quaterniond UpsideDown(const Eigen::Quaterniond& q_true) {
  const Eigen::Vector3d up_B = q_true.conjugate() * Eigen::Vector3d::UnitZ();
  return q_true * Eigen::Quaterniond(Eigen::AngleAxisd(kPi, up_B.unitOrthogonal()));
}

TEST(ImuAttitudeEstimator, ConvergesFromUpsideDownAtRest) {
  ImuAttitudeEstimator estimator;
  estimator.Reset(UpsideDown(kTrueStart));
  RotatingVehicle vehicle(kTrueStart, Eigen::Vector3d::Zero(), 7);
  ASSERT_NEAR(TiltError(vehicle.q_WB(), estimator.q_WB()), kPi, 1e-7);
  const EstimatorRun run = Feed(estimator, vehicle, 3.0, 1.0);
  const double k = estimator.params().correction_gain;
  RecordProperty("convergence_time_s", std::to_string(run.convergence_time_s));
  RecordProperty("steady_rms_rad", std::to_string(run.steady_rms_rad));
  // Noise moves the crossing of 1 deg by a few samples only; 5 % of ~1.03 s is 26 samples.
  EXPECT_NEAR(run.convergence_time_s, PredictedConvergenceTime(k),
              0.05 * PredictedConvergenceTime(k));
  // 500 correlated samples (time constant 100 samples): the RMS estimate is within ~20 %.
  EXPECT_NEAR(run.steady_rms_rad, PredictedSteadyRms(k), 0.3 * PredictedSteadyRms(k));
  // A Rayleigh-distributed error exceeds 4.5 sigma_axis with probability 4e-5 per sample.
  EXPECT_LT(run.steady_max_rad, 4.5 * PredictedSteadyRms(k) / std::sqrt(2.0));
}

TEST(ImuAttitudeEstimator, ConvergesFromUpsideDownWhileRotatingSlowly) {
  // 0.3 rad/s keeps the update gate (|omega| < 0.5 rad/s) open; the gyro carries the rotation.
  const Eigen::Vector3d omega_B = 0.3 * Eigen::Vector3d(1.0, -1.0, 0.5).normalized();
  ImuAttitudeEstimator estimator;
  estimator.Reset(UpsideDown(kTrueStart));
  RotatingVehicle vehicle(kTrueStart, omega_B, 11);
  const EstimatorRun run = Feed(estimator, vehicle, 3.0, 1.0);
  const double k = estimator.params().correction_gain;
  RecordProperty("convergence_time_s", std::to_string(run.convergence_time_s));
  RecordProperty("steady_rms_rad", std::to_string(run.steady_rms_rad));
  EXPECT_NEAR(run.convergence_time_s, PredictedConvergenceTime(k),
              0.05 * PredictedConvergenceTime(k));
  EXPECT_NEAR(run.steady_rms_rad, PredictedSteadyRms(k), 0.3 * PredictedSteadyRms(k));
}

TEST(ImuAttitudeEstimator, FastRotationIsIntegratedWithoutAccelerometerUpdates) {
  // Converge at rest, then spin at 4 rad/s (gate closed: gyro integration (B.22) only). The
  // zero-order integration is exact for constant rates, so the error only grows by the gyro
  // noise random walk sigma_g dt sqrt(n) = 0.002 * 0.002 * sqrt(500) = 9e-5 rad per second.
  ImuAttitudeEstimator estimator;
  estimator.Reset(kTrueStart);
  RotatingVehicle vehicle(kTrueStart, Eigen::Vector3d::Zero(), 3);
  Feed(estimator, vehicle, 1.0, 0.1);
  const double error_before = TiltError(vehicle.q_WB(), estimator.q_WB());
  const Eigen::Quaterniond q_rel_before = vehicle.q_WB().conjugate() * estimator.q_WB();
  vehicle.set_omega_B(Eigen::Vector3d(4.0, -2.0, 1.0));
  int updates = 0;
  for (int k = 0; k < 500; ++k) {
    vehicle.Step();
    updates += estimator.AddImu(vehicle.t(), vehicle.Accel(), vehicle.Gyro()) ? 1 : 0;
  }
  EXPECT_EQ(updates, 0);
  // Full attitude error (yaw included) changes only by the noise random walk: 1e-3 rad is 11x its
  // 1-s standard deviation.
  const Eigen::Quaterniond q_rel_after = vehicle.q_WB().conjugate() * estimator.q_WB();
  EXPECT_LT(q_rel_before.angularDistance(q_rel_after), 1e-3);
  EXPECT_LT(TiltError(vehicle.q_WB(), estimator.q_WB()), error_before + 1e-3);
}

TEST(ImuAttitudeEstimator, InitializesRollPitchFromFirstGravityMeasurement) {
  ImuAttitudeEstimator estimator;
  EXPECT_FALSE(estimator.initialized());
  RotatingVehicle vehicle(kTrueStart, Eigen::Vector3d::Zero(), 5);
  // A sample far from |f| = g (thrown, free fall) is not used for initialization.
  EXPECT_FALSE(estimator.AddImu(0.0, Eigen::Vector3d(0.0, 0.0, 0.3), Eigen::Vector3d::Zero()));
  EXPECT_FALSE(estimator.initialized());
  vehicle.Step();
  EXPECT_TRUE(estimator.AddImu(vehicle.t(), vehicle.Accel(), vehicle.Gyro()));
  EXPECT_TRUE(estimator.initialized());
  // One noisy sample: direction error ~ sqrt(2) sigma_a / g = 7e-3 rad; 4 sigma bound.
  EXPECT_LT(TiltError(vehicle.q_WB(), estimator.q_WB()),
            4.0 * std::sqrt(2.0) * kAccelSigma / kGravity_mps2);
  const Eigen::Vector3d rpy = estimator.RollPitchYawRad();
  EXPECT_NEAR(rpy.x(), 0.2, 0.03);
  EXPECT_NEAR(rpy.y(), -0.1, 0.03);
}

TEST(ImuAttitudeEstimator, GateRejectsAccelerationAwayFromGravity) {
  // A horizontally accelerating vehicle (3 m/s^2 -> |f| = 10.26, gate 1.0 m/s^2 passes) would pull
  // the estimate towards the wrong up direction; one with 5 m/s^2 (|f| = 11.0) is gated out.
  ImuAttitudeEstimator estimator;
  estimator.Reset(Eigen::Quaterniond::Identity());
  const Eigen::Vector3d f_B(5.0, 0.0, kGravity_mps2);
  for (int k = 1; k <= 100; ++k) {
    EXPECT_FALSE(estimator.AddImu(k * kImuDt_s, f_B, Eigen::Vector3d::Zero()));
  }
  EXPECT_NEAR(estimator.TiltRad(), 0.0, 1e-12);
  // And a gated-in sample does correct: tilt moves by k_corr of the 0.29 rad angle.
  const Eigen::Vector3d f_tilted(3.0, 0.0, kGravity_mps2);
  EXPECT_TRUE(estimator.AddImu(101 * kImuDt_s, f_tilted, Eigen::Vector3d::Zero()));
  EXPECT_NEAR(estimator.TiltRad(),
              estimator.params().correction_gain * std::atan2(3.0, kGravity_mps2), 1e-9);
}

TEST(ImuAttitudeEstimator, RemovesCalibratedGyroBias) {
  // A 0.05 rad/s yaw gyro bias (A.17) integrates to 0.1 rad of heading drift in 2 s; with the
  // calibrated bias (A.19) removed the drift is only the noise random walk (~1e-4 rad).
  const Eigen::Vector3d bias(0.01, -0.02, 0.05);
  for (const bool calibrated : {false, true}) {
    ImuAttitudeEstimatorParams params;
    if (calibrated) params.gyro_bias_B = bias;
    ImuAttitudeEstimator estimator(params);
    estimator.Reset(kTrueStart);
    RotatingVehicle vehicle(kTrueStart, Eigen::Vector3d::Zero(), 9);
    for (int k = 0; k < 1000; ++k) {
      vehicle.Step();
      estimator.AddImu(vehicle.t(), vehicle.Accel(), vehicle.Gyro() + bias);
    }
    const double yaw_error = vehicle.q_WB().angularDistance(estimator.q_WB());
    if (calibrated) {
      EXPECT_LT(yaw_error, 2e-3);
    } else {
      EXPECT_GT(yaw_error, 0.08);  // 0.1 rad of yaw drift, tilt part held by the accelerometer
    }
  }
}

TEST(ImuAttitudeEstimator, RejectsBadInput) {
  ImuAttitudeEstimatorParams params;
  params.correction_gain = 1.5;
  EXPECT_THROW(ImuAttitudeEstimator{params}, std::invalid_argument);
  ImuAttitudeEstimator estimator;
  estimator.AddImu(1.0, Eigen::Vector3d(0, 0, kGravity_mps2), Eigen::Vector3d::Zero());
  EXPECT_THROW(estimator.AddImu(1.0, Eigen::Vector3d(0, 0, kGravity_mps2), Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(
      estimator.AddImu(2.0, Eigen::Vector3d(NAN, 0, kGravity_mps2), Eigen::Vector3d::Zero()),
      std::invalid_argument);
  EXPECT_THROW(estimator.Reset(Eigen::Quaterniond(0, 0, 0, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
