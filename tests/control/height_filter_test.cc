#include "control/height_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "control/constants.h"

namespace aperture::control {
namespace {

constexpr double kImuDt = 0.002;  // 500 Hz prediction (B.27)
constexpr int kImuPerRange = 5;   // 100 Hz range updates (B.28), the filter's default period

// Known height profile z(t) = 1.5 + 0.5 sin(2 pi 0.4 t) (a vehicle bobbing in height).
double TrueZ(double t) { return 1.5 + 0.5 * std::sin(2.0 * kPi * 0.4 * t); }
double TrueZDot(double t) { return 0.5 * 2.0 * kPi * 0.4 * std::cos(2.0 * kPi * 0.4 * t); }
double TrueZDdot(double t) {
  return -0.5 * std::pow(2.0 * kPi * 0.4, 2) * std::sin(2.0 * kPi * 0.4 * t);
}

struct TrackingErrors {
  double filter_z_rms = 0.0;
  double range_z_rms = 0.0;
  double filter_z_dot_rms = 0.0;
};

TrackingErrors TrackHeight(double accel_sigma, double range_sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  HeightFilter filter;
  filter.Initialize(TrueZ(0.0), TrueZDot(0.0));
  double sum_f = 0.0, sum_r = 0.0, sum_v = 0.0;
  int n = 0;
  for (int k = 1; k <= 2500; ++k) {  // 5 s
    const double t = k * kImuDt;
    // Acceleration over the step: its midpoint value plus white noise.
    filter.Predict(kImuDt, TrueZDdot(t - 0.5 * kImuDt) + accel_sigma * normal(rng));
    if (k % kImuPerRange == 0) {
      const double z_meas = TrueZ(t) + range_sigma * normal(rng);
      filter.Update(z_meas);
      if (t > 1.0) {  // after the initial transient
        sum_f += std::pow(filter.estimate().z_m - TrueZ(t), 2);
        sum_r += std::pow(z_meas - TrueZ(t), 2);
        sum_v += std::pow(filter.estimate().z_dot_mps - TrueZDot(t), 2);
        ++n;
      }
    }
  }
  return {std::sqrt(sum_f / n), std::sqrt(sum_r / n), std::sqrt(sum_v / n)};
}

TEST(HeightFilter, TracksHeightProfileBetterThanRawRange) {
  // Accelerometer 0.3 m/s^2 per sample, TeraRanger-class range noise 2 cm.
  const TrackingErrors e = TrackHeight(0.3, 0.02, 21);
  RecordProperty("filter_z_rms_m", std::to_string(e.filter_z_rms));
  RecordProperty("range_z_rms_m", std::to_string(e.range_z_rms));
  RecordProperty("filter_z_dot_rms_mps", std::to_string(e.filter_z_dot_rms));
  // The default steady-state gain K_z = 0.13 averages ~ (2 - K_z) / K_z ~ 14 range readings: the
  // range noise's share of the height error is ~ sqrt(K_z / (2 - K_z)) 0.02 = 5 mm.
  EXPECT_LT(e.filter_z_rms, 0.7 * e.range_z_rms);
  EXPECT_NEAR(e.range_z_rms, 0.02, 0.003);  // sanity of the simulated sensor (400 samples)
  // A finite difference of the range would have sqrt(2) 0.02 / 0.01 = 2.8 m/s of noise; the
  // filter's velocity error is an order of magnitude below the 0.3 m/s stage threshold of B.3.2.
  EXPECT_LT(e.filter_z_dot_rms, 0.05);
}

TEST(HeightFilter, PredictionIsExactForConstantAcceleration) {
  // (B.27) is the exact discretization for a constant acceleration: noise-free data keep the
  // innovation at zero to rounding.
  HeightFilter filter;
  filter.Initialize(0.5, -1.0);
  const double a = 1.7;
  for (int k = 1; k <= 1000; ++k) {
    filter.Predict(kImuDt, a);
    const double t = k * kImuDt;
    if (k % kImuPerRange == 0) filter.Update(0.5 - 1.0 * t + 0.5 * a * t * t);
  }
  const double t = 1000 * kImuDt;
  EXPECT_NEAR(filter.estimate().z_m, 0.5 - t + 0.5 * a * t * t, 1e-9);
  EXPECT_NEAR(filter.estimate().z_dot_mps, -1.0 + a * t, 1e-9);
  EXPECT_NEAR(filter.estimate().time_since_init_s, t, 1e-12);
}

TEST(HeightFilter, UnknownInitialVelocityConvergesWithinRecoverySettlingTime) {
  // Recovery initializes the filter with z_dot = 0 while the vehicle still moves at up to a few
  // m/s (B.3.2, stage 2). With the default gain the velocity error must drop below the 0.3 m/s
  // stage-2 threshold within RecoveryParams::min_height_filter_time_s = 0.3 s from 3 m/s.
  HeightFilter filter;
  const double v = -3.0;
  filter.Initialize(2.0, 0.0);
  double t = 0.0;
  for (int k = 1; k <= 150; ++k) {  // 0.3 s
    t = k * kImuDt;
    filter.Predict(kImuDt, 0.0);
    if (k % kImuPerRange == 0) filter.Update(2.0 + v * t);
  }
  RecordProperty("velocity_error_after_0_3s_mps", std::to_string(filter.estimate().z_dot_mps - v));
  EXPECT_LT(std::abs(filter.estimate().z_dot_mps - v), 0.3);
}

TEST(HeightFilter, SteadyStateGainIsAFixedPointOfTheRiccatiRecursion) {
  const double dt = 0.01, sa = 2.0, sr = 0.02;
  const Eigen::Vector2d K = HeightFilter::ComputeSteadyStateGain(dt, sa, sr);
  // The steady-state error covariance of the closed loop (I - K H) F must reproduce K: solve the
  // discrete Lyapunov-type fixed point by iterating the *fixed-gain* covariance recursion.
  Eigen::Matrix2d F;
  F << 1, dt, 0, 1;
  const Eigen::Vector2d G(0.5 * dt * dt, dt);
  const Eigen::Matrix2d Q = sa * sa * G * G.transpose();
  Eigen::Matrix2d P_prior = Eigen::Matrix2d::Identity();
  const Eigen::RowVector2d H(1, 0);
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Matrix2d A = Eigen::Matrix2d::Identity() - K * H;
    const Eigen::Matrix2d P_post = A * P_prior * A.transpose() + sr * sr * K * K.transpose();
    P_prior = F * P_post * F.transpose() + Q;
  }
  const Eigen::Vector2d K_opt = P_prior.col(0) / (P_prior(0, 0) + sr * sr);
  EXPECT_NEAR(K(0), K_opt(0), 1e-9);
  EXPECT_NEAR(K(1), K_opt(1), 1e-7);
  HeightFilter filter;
  EXPECT_NEAR(filter.gain_K()(0), K(0), 1e-15);  // defaults: dt = 0.01, 2.0, 0.02
}

TEST(HeightFilter, HeightFromTiltedRangeAndVerticalAcceleration) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized()));
  EXPECT_NEAR(*HeightFilter::HeightFromRange(2.0, q), 2.0 * std::cos(0.3), 1e-12);
  const Eigen::Quaterniond upside_down(Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()));
  EXPECT_FALSE(HeightFilter::HeightFromRange(2.0, upside_down).has_value());
  // Thrust c along a tilted z_B: only its vertical component c cos(tilt) acts against gravity.
  const double c = 12.0;
  EXPECT_NEAR(HeightFilter::VerticalAcceleration(q, Eigen::Vector3d(0, 0, c), 9.81),
              c * std::cos(0.3) - 9.81, 1e-12);
}

TEST(HeightFilter, RejectsBadUse) {
  HeightFilter filter;
  EXPECT_THROW(filter.Predict(0.01, 0.0), std::logic_error);
  EXPECT_THROW(filter.Update(1.0), std::logic_error);
  filter.Initialize(1.0);
  EXPECT_THROW(filter.Predict(0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(filter.Update(NAN), std::invalid_argument);
  HeightFilterParams params;
  params.range_noise_sigma_m = 0.0;
  EXPECT_THROW(HeightFilter{params}, std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
