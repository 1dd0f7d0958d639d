// PoseImuFilter on analytic trajectories: the IMU is generated exactly from the flat outputs of
// the thesis circle (specific force R^T (a + g z_W), body rates from flatness), optionally with
// synthetic noise and constant biases.
#include "perception/estimation/pose_imu_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/flatness.h"
#include "control/reference_trajectories.h"
#include "perception/camera/optical_axes.h"

namespace aperture::perception {
namespace {

constexpr double kImuRateHz = 500.0;
constexpr double kImuDt = 1.0 / kImuRateHz;

struct TruthSample {
  control::QuadState state;
  Eigen::Vector3d specific_force_B;
};

// Truth of the 4 m/s, 1.8 m circle (|omega| up to 85 deg/s, c = 13.2 m/s^2) without rotor drag, so
// that flatness gives the exact body rates of R_WB(t).
class CircleTruth {
 public:
  CircleTruth() : trajectory_(CircleParams()) { vehicle_.rotor_drag_D_per_s.setZero(); }

  TruthSample At(double t_s) const {
    const control::TrajectoryPoint point = trajectory_.Evaluate(t_s);
    const control::FlatnessResult flat = control::ComputeFlatnessOutputs(point, vehicle_);
    TruthSample truth;
    truth.state.t_s = t_s;
    truth.state.p_WB = point.p_W;
    truth.state.v_W = point.v_W;
    truth.state.q_WB = flat.q_WB;
    truth.state.omega_B = flat.omega_B;
    truth.specific_force_B =
        flat.R_WB.transpose() * (point.a_W + Eigen::Vector3d(0, 0, vehicle_.gravity_mps2));
    return truth;
  }

 private:
  static control::CircleTrajectoryParams CircleParams() {
    control::CircleTrajectoryParams params;
    params.ramp.ramp_s = 1.0;  // reach full speed quickly to keep the tests short
    params.ramp.num_loops = 100.0;
    return params;
  }
  control::CircleTrajectory trajectory_;
  control::VehicleParameters vehicle_;
};

// Synthetic IMU with the filter's noise model: white noise of density sigma sampled as
// N(0, sigma^2 / dt) and constant biases.
class SyntheticImu {
 public:
  SyntheticImu(double accel_density, double gyro_density, const Eigen::Vector3d& accel_bias,
               const Eigen::Vector3d& gyro_bias, std::uint64_t seed, double dt_s = kImuDt)
      : accel_sigma_(accel_density / std::sqrt(dt_s)),
        gyro_sigma_(gyro_density / std::sqrt(dt_s)),
        accel_bias_(accel_bias),
        gyro_bias_(gyro_bias),
        rng_(seed) {}

  ImuSample Measure(const TruthSample& truth) {
    ImuSample sample;
    sample.t_s = truth.state.t_s;
    sample.specific_force_B = truth.specific_force_B + accel_bias_ + Noise(accel_sigma_);
    sample.omega_B = truth.state.omega_B + gyro_bias_ + Noise(gyro_sigma_);
    return sample;
  }
  Eigen::Vector3d Noise(double sigma) {
    return sigma * Eigen::Vector3d(normal_(rng_), normal_(rng_), normal_(rng_));
  }

 private:
  double accel_sigma_, gyro_sigma_;
  Eigen::Vector3d accel_bias_, gyro_bias_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

double AttitudeError(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::AngleAxisd(a.conjugate() * b).angle();
}

// Pose of X = camera 10 cm forward of B, looking along x_B (OpenCV axes).
PoseMeasurement CameraExtrinsics() {
  PoseMeasurement z;
  z.p_BX = Eigen::Vector3d(0.1, 0.0, 0.02);
  const Eigen::Matrix3d R_BC =
      perception::OpticalAxesAlongX();  // z_C = x_B, x_C = -y_B, y_C = -z_B
  z.q_BX = Eigen::Quaterniond(R_BC);
  return z;
}

// Noisy pose of X: p_WX + n_p, R_WX Exp(n_theta).
PoseMeasurement MeasurePose(const control::QuadState& truth, const PoseMeasurement& extrinsics,
                            double sigma_p, double sigma_theta, SyntheticImu* rng) {
  PoseMeasurement z = extrinsics;
  z.t_s = truth.t_s;
  z.p_WX = truth.p_WB + truth.q_WB * extrinsics.p_BX + rng->Noise(sigma_p);
  const Eigen::Vector3d n_theta = rng->Noise(sigma_theta);
  z.q_WX = truth.q_WB * extrinsics.q_BX;
  if (n_theta.norm() > 0.0) {
    z.q_WX = z.q_WX * Eigen::Quaterniond(Eigen::AngleAxisd(n_theta.norm(), n_theta.normalized()));
  }
  z.q_WX.normalize();
  z.covariance.setZero();
  z.covariance.topLeftCorner<3, 3>().diagonal().setConstant(sigma_p * sigma_p);
  z.covariance.bottomRightCorner<3, 3>().diagonal().setConstant(sigma_theta * sigma_theta);
  return z;
}

struct PropagationError {
  double max_p = 0, max_v = 0, max_theta = 0;
};

// Pure propagation (no updates) over 5 s of the circle (ramp plus > 1.5 loops) from the true
// state, with a noise-free IMU at `rate_hz` carrying known constant biases.
PropagationError PropagateNoiseFree(double rate_hz) {
  const CircleTruth circle;
  const double dt = 1.0 / rate_hz;
  const Eigen::Vector3d b_a(0.05, -0.08, 0.1), b_g(0.01, -0.02, 0.005);
  SyntheticImu imu(0.0, 0.0, b_a, b_g, 1, dt);
  PoseImuEstimate initial;
  initial.state = circle.At(0.0).state;
  initial.accel_bias_B = b_a;  // known biases: they must be removed exactly
  initial.gyro_bias_B = b_g;
  initial.covariance = Matrix15d::Identity() * 1e-4;
  PoseImuFilter filter(PoseImuFilterParams{}, initial);
  const int steps = static_cast<int>(std::lround(5.0 * rate_hz));
  PropagationError error;
  for (int k = 1; k <= steps; ++k) {
    const TruthSample truth = circle.At(k * dt);
    filter.Propagate(imu.Measure(truth));
    const PoseImuEstimate estimate = filter.Estimate();
    error.max_p = std::max(error.max_p, (estimate.state.p_WB - truth.state.p_WB).norm());
    error.max_v = std::max(error.max_v, (estimate.state.v_W - truth.state.v_W).norm());
    error.max_theta =
        std::max(error.max_theta, AttitudeError(estimate.state.q_WB, truth.state.q_WB));
    // Rates are reported bias-corrected.
    EXPECT_LT((estimate.state.omega_B - truth.state.omega_B).norm(), 1e-12);
  }
  return error;
}

TEST(PoseImuFilterTest, NoiseFreePropagationFollowsCircleWithSecondOrderError) {
  const PropagationError e500 = PropagateNoiseFree(500.0);
  const PropagationError e250 = PropagateNoiseFree(250.0);
  std::printf(
      "noise-free propagation over 5 s at 500 Hz: max |dp| %.3g m, |dv| %.3g m/s, "
      "dtheta %.3g rad; at 250 Hz: %.3g m, %.3g m/s, %.3g rad\n",
      e500.max_p, e500.max_v, e500.max_theta, e250.max_p, e250.max_v, e250.max_theta);
  // The trapezoid rule on linearly interpolated inputs has a local error dt^3/12 |omega''| with
  // |omega''| ~ |omega| (v/r)^2 ~ 7 rad/s^3 on this circle: ~5e-9 rad per 2 ms step, ~1e-5 rad
  // after 2500 steps, which tilts the gravity compensation and drifts v and p (~1e-3 m/s, ~1e-3 m
  // over 5 s). That is 10x below the gyro noise alone (8.7e-5 rad/s/sqrt(Hz) -> 2e-4 rad in 5 s).
  EXPECT_LT(e500.max_theta, 4e-5);
  EXPECT_LT(e500.max_v, 1e-3);
  EXPECT_LT(e500.max_p, 2e-3);
  // A correct second-order integrator quarters its global error when dt halves; a wrong sign or
  // a missing term anywhere (bias, gravity, frame) would give an O(1) or O(dt) error instead.
  EXPECT_NEAR(e250.max_theta / e500.max_theta, 4.0, 0.6);
  EXPECT_NEAR(e250.max_p / e500.max_p, 4.0, 0.6);
}

// The covariance transition must be the Jacobian of the nominal propagation: with no process
// noise and P0 = eps^2 I, P(T) = eps^2 Phi Phi^T, and the columns of Phi can be measured by
// propagating the nominal state perturbed by h e_i (x0 [+] h e_i) and comparing with the
// unperturbed run (x [-] x_ref) / h.
TEST(PoseImuFilterTest, CovariancePropagationMatchesNumericJacobian) {
  const CircleTruth circle;
  const double t0 = 2.0;  // at full speed: |omega| ~ 85 deg/s, tilted thrust
  const int steps = 50;   // 0.1 s
  PoseImuFilterParams params;
  params.accel_noise_density = params.gyro_noise_density = 0.0;
  params.accel_bias_random_walk = params.gyro_bias_random_walk = 0.0;
  SyntheticImu imu(0.0, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 1);
  std::vector<ImuSample> samples;
  for (int k = 0; k <= steps; ++k) samples.push_back(imu.Measure(circle.At(t0 + k * kImuDt)));

  const double eps = 1e-3;
  auto run = [&](const Vector15d& dx) {
    PoseImuEstimate initial;
    initial.state = circle.At(t0).state;
    initial.state.p_WB += dx.segment<3>(ErrorStateIndex::kPosition);
    initial.state.v_W += dx.segment<3>(ErrorStateIndex::kVelocity);
    initial.state.q_WB =
        (initial.state.q_WB * Eigen::Quaterniond(Eigen::AngleAxisd(
                                  dx.segment<3>(ErrorStateIndex::kAttitude).norm(),
                                  dx.segment<3>(ErrorStateIndex::kAttitude).normalized())))
            .normalized();
    initial.accel_bias_B = dx.segment<3>(ErrorStateIndex::kAccelBias);
    initial.gyro_bias_B = dx.segment<3>(ErrorStateIndex::kGyroBias);
    initial.covariance = Matrix15d::Identity() * eps * eps;
    PoseImuFilter filter(params, initial);
    for (const ImuSample& sample : samples) filter.Propagate(sample);
    return filter.Estimate();
  };
  const PoseImuEstimate reference = run(Vector15d::Zero());
  Matrix15d Phi_numeric;
  const double h = 1e-6;
  for (int i = 0; i < 15; ++i) {
    Vector15d dx = Vector15d::Zero();
    dx(i) = h;
    const PoseImuEstimate e = run(dx);
    Vector15d diff;
    const Eigen::AngleAxisd dtheta(reference.state.q_WB.conjugate() * e.state.q_WB);
    diff << e.state.p_WB - reference.state.p_WB, e.state.v_W - reference.state.v_W,
        dtheta.angle() * dtheta.axis(), e.accel_bias_B - reference.accel_bias_B,
        e.gyro_bias_B - reference.gyro_bias_B;
    Phi_numeric.col(i) = diff / h;
  }
  const Matrix15d expected = Phi_numeric * Phi_numeric.transpose();
  const Matrix15d actual = reference.covariance / (eps * eps);
  const double error = (actual - expected).cwiseAbs().maxCoeff();
  std::printf("covariance vs numeric Jacobian: max |diff| %.3g of max entry %.3g\n", error,
              expected.cwiseAbs().maxCoeff());
  // Finite differences with h = 1e-6 on O(1) states carry ~1e-16 / 1e-6 = 1e-10 of round-off
  // and O(h) = 1e-6 of truncation;
  // Phi is linearized at the mid-interval rotation and mean inputs, which differs from the exact
  // derivative of the trapezoid step by O(dt^2 |omega|^2) ~ 1e-5 per step. A sign or block
  // error (e.g. -R [f]x vs R [f]x) gives differences of O(|f| T) ~ 1.
  // Measured 1.3e-6 relative.
  EXPECT_LT(error, 1e-4 * expected.cwiseAbs().maxCoeff());
}

struct RunResult {
  PoseImuEstimate final_estimate;
  control::QuadState final_truth;
  int rejected = 0;
};

// Runs the filter on the circle with noisy IMU and 30 Hz camera poses from a wrong initial state.
RunResult RunCircle(double duration_s, const Eigen::Vector3d& b_a, const Eigen::Vector3d& b_g,
                    std::uint64_t seed) {
  const CircleTruth circle;
  PoseImuFilterParams params;
  SyntheticImu imu(params.accel_noise_density, params.gyro_noise_density, b_a, b_g, seed);
  control::QuadState initial = circle.At(0.0).state;
  initial.p_WB += Eigen::Vector3d(0.4, -0.3, 0.2);
  initial.v_W += Eigen::Vector3d(-0.3, 0.2, 0.1);
  initial.q_WB = initial.q_WB *
                 Eigen::Quaterniond(Eigen::AngleAxisd(0.15, Eigen::Vector3d(1, 1, 0).normalized()));
  PoseImuFilter filter(params, initial);  // biases start at 0
  const PoseMeasurement extrinsics = CameraExtrinsics();
  RunResult result;
  const int steps = static_cast<int>(duration_s * kImuRateHz);
  double next_pose_s = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const TruthSample truth = circle.At(k * kImuDt);
    filter.Propagate(imu.Measure(truth));
    if (truth.state.t_s >= next_pose_s) {
      next_pose_s += 1.0 / 30.0;
      const PoseUpdateResult update =
          filter.Update(MeasurePose(truth.state, extrinsics, 0.02, 0.01, &imu));
      if (!update.applied()) ++result.rejected;
    }
    result.final_truth = truth.state;
  }
  result.final_estimate = filter.Estimate();
  return result;
}

TEST(PoseImuFilterTest, ConvergesFromWrongInitialStateAndEstimatesBiases) {
  const Eigen::Vector3d b_a(0.08, -0.06, 0.12), b_g(0.008, -0.006, 0.004);
  const RunResult run = RunCircle(20.0, b_a, b_g, 7);
  const PoseImuEstimate& e = run.final_estimate;
  const Vector15d sigma = e.covariance.diagonal().cwiseSqrt();
  const double dp = (e.state.p_WB - run.final_truth.p_WB).norm();
  const double dv = (e.state.v_W - run.final_truth.v_W).norm();
  const double dtheta = AttitudeError(e.state.q_WB, run.final_truth.q_WB);
  std::printf(
      "after 20 s: |dp| %.4f m, |dv| %.4f m/s, dtheta %.5f rad, |db_a| %.4f m/s^2, "
      "|db_g| %.5f rad/s; sigma_ba %.4f, sigma_bg %.5f; rejected %d\n",
      dp, dv, dtheta, (e.accel_bias_B - b_a).norm(), (e.gyro_bias_B - b_g).norm(),
      sigma.segment<3>(ErrorStateIndex::kAccelBias).maxCoeff(),
      sigma.segment<3>(ErrorStateIndex::kGyroBias).maxCoeff(), run.rejected);
  // Initial errors were 0.54 m, 0.37 m/s, 0.15 rad and 0.16 m/s^2, 0.011 rad/s of bias. With
  // 2 cm / 0.01 rad poses at 30 Hz the steady state is at the cm / mrad level; 4 sigma bounds of
  // a 3-dof error (|e| < 4 max sigma sqrt(3)) plus an absolute check that it did converge.
  auto bound = [&](int block) { return 4.0 * std::sqrt(3.0) * sigma.segment<3>(block).maxCoeff(); };
  EXPECT_LT(dp, bound(ErrorStateIndex::kPosition));
  EXPECT_LT(dv, bound(ErrorStateIndex::kVelocity));
  EXPECT_LT(dtheta, bound(ErrorStateIndex::kAttitude));
  EXPECT_LT((e.accel_bias_B - b_a).norm(), bound(ErrorStateIndex::kAccelBias));
  EXPECT_LT((e.gyro_bias_B - b_g).norm(), bound(ErrorStateIndex::kGyroBias));
  EXPECT_LT(dp, 0.03);
  EXPECT_LT(dtheta, 0.01);
  // Biases converge to a fraction of the injected ones (their initial error).
  EXPECT_LT((e.accel_bias_B - b_a).norm(), 0.2 * b_a.norm());
  EXPECT_LT((e.gyro_bias_B - b_g).norm(), 0.1 * b_g.norm());
  EXPECT_LE(run.rejected, 1);  // 99.9 % gate, ~600 inliers
}

// Feeds the same IMU and poses into two filters: one gets each pose as soon as the IMU has
// reached its stamp, the other `delay_samples` IMU samples later.
struct DelayComparison {
  double max_dp = 0, max_dv = 0, max_dtheta = 0, max_dP = 0;
  int comparisons = 0;
  double naive_dp = 0;  // same delay, pose applied as if taken at arrival (no latency handling)
};

DelayComparison CompareDelayed(int delay_samples, bool stamps_on_imu_grid) {
  const CircleTruth circle;
  PoseImuFilterParams params;
  SyntheticImu imu(params.accel_noise_density, params.gyro_noise_density,
                   Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d(0, 0.005, 0), 3);
  control::QuadState initial = circle.At(0.0).state;
  initial.p_WB += Eigen::Vector3d(0.2, 0.1, -0.1);
  PoseImuFilterParams naive_params = params;
  naive_params.mahalanobis_gate = std::numeric_limits<double>::infinity();
  PoseImuFilter on_time(params, initial), delayed(params, initial), naive(naive_params, initial);
  const PoseMeasurement extrinsics = CameraExtrinsics();
  struct InFlight {
    int arrival_step;
    PoseMeasurement pose;
    PoseUpdateStatus on_time_status;
  };
  std::vector<InFlight> in_flight;
  DelayComparison out;
  const int steps = static_cast<int>(4.0 * kImuRateHz);
  int next_pose_index = 0;
  for (int k = 1; k <= steps; ++k) {
    const ImuSample sample = imu.Measure(circle.At(k * kImuDt));
    on_time.Propagate(sample);
    delayed.Propagate(sample);
    naive.Propagate(sample);
    // Poses every 16 samples (31.25 Hz) on the grid, or at 30 Hz between samples.
    const double t_pose =
        stamps_on_imu_grid ? next_pose_index * 16 * kImuDt : next_pose_index / 30.0;
    // Poses only during the first 3.5 s, so that the delayed filter catches up afterwards.
    if (t_pose <= sample.t_s && t_pose < 3.5) {
      const PoseMeasurement z = MeasurePose(circle.At(t_pose).state, extrinsics, 0.02, 0.01, &imu);
      in_flight.push_back({k + delay_samples, z, on_time.Update(z).status});
      ++next_pose_index;
    }
    while (!in_flight.empty() && in_flight.front().arrival_step == k) {
      const PoseUpdateResult r = delayed.Update(in_flight.front().pose);
      EXPECT_EQ(r.status, in_flight.front().on_time_status) << r;
      EXPECT_GE(r.replayed_steps, delay_samples);
      PoseMeasurement z_naive = in_flight.front().pose;
      z_naive.t_s = sample.t_s;
      naive.Update(z_naive);
      in_flight.erase(in_flight.begin());
    }
    if (in_flight.empty() && next_pose_index > 0) {
      // Both filters have now seen the same poses: compare.
      const PoseImuEstimate a = on_time.Estimate(), b = delayed.Estimate();
      out.max_dp = std::max(out.max_dp, (a.state.p_WB - b.state.p_WB).norm());
      out.max_dv = std::max(out.max_dv, (a.state.v_W - b.state.v_W).norm());
      out.max_dtheta = std::max(out.max_dtheta, AttitudeError(a.state.q_WB, b.state.q_WB));
      out.max_dP = std::max(out.max_dP, (a.covariance - b.covariance).cwiseAbs().maxCoeff());
      ++out.comparisons;
    }
    if (k > steps / 2 && k < 3.5 * kImuRateHz) {
      const control::QuadState truth = circle.At(sample.t_s).state;
      out.naive_dp = std::max(out.naive_dp, (naive.Estimate().state.p_WB - truth.p_WB).norm());
    }
  }
  return out;
}

class PoseImuFilterDelayTest : public ::testing::TestWithParam<bool> {};

TEST_P(PoseImuFilterDelayTest, DelayedMeasurementsGiveTheOnTimeEstimate) {
  const int kDelaySamples = 25;  // 50 ms at 500 Hz
  const DelayComparison c = CompareDelayed(kDelaySamples, GetParam());
  std::printf(
      "50 ms latency vs on time: max |dp| %.3g m, |dv| %.3g m/s, dtheta %.3g rad, "
      "|dP| %.3g; naive (applied at arrival) |p err| %.3g m\n",
      c.max_dp, c.max_dv, c.max_dtheta, c.max_dP, c.naive_dp);
  // Both filters run the same arithmetic on the same inputs (the re-propagation replays the
  // stored samples, interpolated identically at the pose stamp); differences are round-off.
  EXPECT_LT(c.max_dp, 1e-9);
  EXPECT_LT(c.max_dv, 1e-9);
  EXPECT_LT(c.max_dtheta, 1e-9);
  EXPECT_LT(c.max_dP, 1e-12);
  EXPECT_GT(c.comparisons, 200);  // the last 0.45 s
  // Without latency handling the 50 ms old pose of a 4 m/s vehicle is 0.2 m off.
  EXPECT_GT(c.naive_dp, 0.05);
}

INSTANTIATE_TEST_SUITE_P(StampsOnAndBetweenImuSamples, PoseImuFilterDelayTest,
                         ::testing::Values(true, false));

TEST(PoseImuFilterTest, HistoryIsBoundedAndOldOrFutureMeasurementsAreReported) {
  const CircleTruth circle;
  PoseImuFilterParams params;
  params.history_duration_s = 0.1;
  PoseImuFilter filter(params, circle.At(0.0).state);
  SyntheticImu imu(0.0, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 1);
  for (int k = 1; k <= 500; ++k) filter.Propagate(imu.Measure(circle.At(k * kImuDt)));
  // 0.1 s at 500 Hz: 50 intervals, so 51 entries (plus the one at the boundary).
  EXPECT_LE(filter.history_size(), 52u);
  EXPECT_GE(filter.history_size(), 51u);
  PoseMeasurement z = MeasurePose(circle.At(0.85).state, PoseMeasurement{}, 0.0, 0.0, &imu);
  z.covariance = Matrix6d::Identity() * 1e-4;
  EXPECT_EQ(filter.Update(z).status, PoseUpdateStatus::kTooOld);
  z.t_s = 1.01;
  EXPECT_EQ(filter.Update(z).status, PoseUpdateStatus::kAheadOfImu);
  z = MeasurePose(circle.At(0.951).state, PoseMeasurement{}, 0.0, 0.0, &imu);
  z.covariance = Matrix6d::Identity() * 1e-4;
  const PoseUpdateResult r = filter.Update(z);
  EXPECT_TRUE(r.applied()) << r;
  EXPECT_EQ(r.replayed_steps, 25);  // samples at 0.952 ... 1.000
}

// Measurement Jacobian and error injection together: a near-exact measurement (tiny covariance)
// of a sensor on a 0.5 m lever arm, taken from a state 1 cm / 0.05 rad away from the estimate,
// must move the predicted pose onto the measurement up to the second-order linearization error.
TEST(PoseImuFilterTest, ExactPoseUpdateMovesPredictionOntoMeasurement) {
  const CircleTruth circle;
  const control::QuadState truth = circle.At(2.0).state;
  PoseImuEstimate initial;
  initial.state = truth;
  initial.state.p_WB += Eigen::Vector3d(0.01, -0.005, 0.008);
  initial.state.q_WB = (truth.q_WB * Eigen::Quaterniond(Eigen::AngleAxisd(
                                         0.05, Eigen::Vector3d(1, -2, 0.5).normalized())))
                           .normalized();
  initial.covariance = Matrix15d::Identity();  // 1 m, 1 rad: the measurement dominates
  PoseImuFilterParams params;
  params.mahalanobis_gate = std::numeric_limits<double>::infinity();
  PoseImuFilter filter(params, initial);
  PoseMeasurement z = CameraExtrinsics();
  z.p_BX = Eigen::Vector3d(0.5, -0.2, 0.1);
  z.t_s = truth.t_s;
  z.p_WX = truth.p_WB + truth.q_WB * z.p_BX;
  z.q_WX = truth.q_WB * z.q_BX;
  z.covariance = Matrix6d::Identity() * 1e-12;
  const PoseUpdateResult first = filter.Update(z);
  ASSERT_TRUE(first.applied()) << first;
  const PoseUpdateResult second = filter.Update(z);  // residual of the corrected state
  std::printf("exact update: residual %.3g m, %.3g rad -> %.3g m, %.3g rad\n",
              first.residual.head<3>().norm(), first.residual.tail<3>().norm(),
              second.residual.head<3>().norm(), second.residual.tail<3>().norm());
  // The lever arm turns the 0.05 rad error into ~2.7 cm of position residual; a wrong sign of
  // -R [p_BX]x or of the rotation block would leave residuals of that size. What remains is
  // second order: |dtheta|^2 |p_BX| / 2 ~ 7e-4 m and |dtheta|^2 / 2 ~ 1.3e-3 rad at most.
  EXPECT_GT(first.residual.head<3>().norm(), 0.02);
  EXPECT_LT(second.residual.head<3>().norm(), 2e-3);
  EXPECT_LT(second.residual.tail<3>().norm(), 2e-3);
  EXPECT_LT((filter.Estimate().state.p_WB - truth.p_WB).norm(), 2e-3);
  EXPECT_LT(AttitudeError(filter.Estimate().state.q_WB, truth.q_WB), 2e-3);
}

TEST(PoseImuFilterTest, OutlierIsGatedAndReported) {
  const CircleTruth circle;
  PoseImuFilterParams params;
  PoseImuEstimate initial;
  initial.state = circle.At(0.0).state;
  initial.covariance = Matrix15d::Identity() * 1e-4;  // 1 cm, 1 cm/s, 10 mrad
  PoseImuFilter filter(params, initial);
  SyntheticImu imu(0.0, 0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 1);
  filter.Propagate(imu.Measure(circle.At(kImuDt)));
  PoseMeasurement z = MeasurePose(circle.At(kImuDt).state, PoseMeasurement{}, 0.0, 0.0, &imu);
  z.covariance = Matrix6d::Identity() * 1e-4;
  z.p_WX.x() += 0.5;  // 0.5 m jump against ~1.4 cm of combined sigma
  const PoseImuEstimate before = filter.Estimate();
  const PoseUpdateResult outlier = filter.Update(z);
  EXPECT_EQ(outlier.status, PoseUpdateStatus::kRejectedOutlier) << outlier;
  // d^2 = 0.5^2 / (P_xx + R_xx) with P_xx ~ 1e-4 + propagation, R_xx = 1e-4: ~1250.
  EXPECT_NEAR(outlier.mahalanobis_sq, 0.25 / 2e-4, 0.05 * 0.25 / 2e-4);
  EXPECT_NEAR(outlier.residual.x(), 0.5, 1e-6);
  EXPECT_TRUE(filter.Estimate().state.p_WB.isApprox(before.state.p_WB, 0.0));
  EXPECT_TRUE(filter.Estimate().covariance.isApprox(before.covariance, 0.0));
  z.p_WX.x() -= 0.5;
  const PoseUpdateResult inlier = filter.Update(z);
  EXPECT_TRUE(inlier.applied()) << inlier;
  EXPECT_LT(inlier.mahalanobis_sq, 1e-6);  // noise-free measurement of the true pose
}

// A vehicle at rest 1 m up whose accelerometer reads 0.2 m/s^2 too much along z_B: on the IMU
// alone its height drifts by 0.1 t^2 (0.4 m in 2 s); a 100 Hz height measurement (2 cm, 20 ms
// late) holds it within a few cm, the filter learns the bias, and x, y are not touched. A height
// 1 m off is gated out by chi-square(1) and reported in residual element 2.
TEST(PoseImuFilterTest, HeightMeasurementsHoldTheHeightAndLearnTheVerticalBias) {
  control::QuadState rest;
  rest.p_WB = Eigen::Vector3d(0.3, -0.2, 1.0);
  PoseImuFilterParams params;
  PoseImuFilter with_height(params, rest);
  PoseImuFilter imu_only(params, rest);
  ImuSample sample;
  sample.specific_force_B = Eigen::Vector3d(0.0, 0.0, params.gravity_mps2 + 0.2);
  for (int k = 1; k <= 1000; ++k) {  // 2 s at 500 Hz
    sample.t_s = k * kImuDt;
    with_height.Propagate(sample);
    imu_only.Propagate(sample);
    if (k % 5 == 0 && k >= 10) {
      const PoseUpdateResult r =
          with_height.Update(HeightMeasurement{sample.t_s - 0.02, 1.0, 4e-4});
      ASSERT_TRUE(r.applied()) << "t = " << sample.t_s << " " << r;
    }
  }
  EXPECT_NEAR(imu_only.Estimate().state.p_WB.z(), 1.4, 0.01);
  const PoseImuEstimate e = with_height.Estimate();
  EXPECT_NEAR(e.state.p_WB.z(), 1.0, 0.03);
  EXPECT_NEAR(e.state.v_W.z(), 0.0, 0.05);
  EXPECT_NEAR(e.accel_bias_B.z(), 0.2, 0.05);
  EXPECT_EQ(e.state.p_WB.head<2>(), rest.p_WB.head<2>());

  const PoseUpdateResult outlier = with_height.Update(HeightMeasurement{sample.t_s, 2.0, 4e-4});
  EXPECT_EQ(outlier.status, PoseUpdateStatus::kRejectedOutlier) << outlier;
  EXPECT_DOUBLE_EQ(outlier.gate, params.height_mahalanobis_gate);
  EXPECT_NEAR(outlier.residual(2), 1.0 - (e.state.p_WB.z() - 1.0), 1e-9);
  EXPECT_EQ(outlier.residual.norm(), std::abs(outlier.residual(2)));
  EXPECT_THROW(with_height.Update(HeightMeasurement{sample.t_s, 1.0, 0.0}), std::invalid_argument);
}

// A height corrects the vertical channel only: with x and z strongly correlated (as after an
// open-loop manoeuvre), a 5 cm height residual moves z, not x, and leaves a covariance that is
// still symmetric positive definite with a smaller z variance.
TEST(PoseImuFilterTest, AHeightLeavesTheHorizontalStateAloneDespiteCorrelations) {
  PoseImuEstimate initial;
  initial.state.p_WB = Eigen::Vector3d(1.0, 0.0, 1.0);
  initial.covariance = Matrix15d::Identity() * 1e-2;
  initial.covariance(0, 2) = initial.covariance(2, 0) = 0.9e-2;  // x, z correlated 0.9
  PoseImuFilter filter(PoseImuFilterParams{}, initial);
  const PoseUpdateResult r = filter.Update(HeightMeasurement{0.0, 1.05, 4e-4});
  ASSERT_TRUE(r.applied()) << r;
  const PoseImuEstimate e = filter.Estimate();
  EXPECT_NEAR(e.state.p_WB.z(), 1.0 + 0.05 * 1e-2 / (1e-2 + 4e-4), 1e-9);
  EXPECT_EQ(e.state.p_WB.x(), 1.0);
  EXPECT_LT(e.covariance(2, 2), 1e-3);
  EXPECT_TRUE(e.covariance.isApprox(e.covariance.transpose(), 1e-12));
  EXPECT_EQ(Eigen::LLT<Matrix15d>(e.covariance).info(), Eigen::Success);
}

TEST(PoseImuFilterTest, RejectsNonFiniteInputsNamingThem) {
  PoseImuFilter filter(PoseImuFilterParams{}, control::QuadState{});
  auto expect_throw_naming = [](const auto& call, const std::string& name) {
    try {
      call();
      ADD_FAILURE() << "no exception for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ImuSample sample;
  sample.t_s = 0.01;
  sample.specific_force_B = Eigen::Vector3d(0, nan, 9.81);
  expect_throw_naming([&] { filter.Propagate(sample); }, "specific_force_B");
  sample.specific_force_B = Eigen::Vector3d(0, 0, 9.81);
  sample.omega_B.x() = std::numeric_limits<double>::infinity();
  expect_throw_naming([&] { filter.Propagate(sample); }, "omega_B");
  sample.omega_B.setZero();
  sample.t_s = nan;
  expect_throw_naming([&] { filter.Propagate(sample); }, "t_s");
  sample.t_s = 0.01;
  filter.Propagate(sample);
  sample.t_s = 0.005;
  expect_throw_naming([&] { filter.Propagate(sample); }, "t_s");

  PoseMeasurement z;
  z.t_s = 0.01;
  z.p_WX.z() = nan;
  expect_throw_naming([&] { filter.Update(z); }, "p_WX");
  z.p_WX.setZero();
  z.covariance(3, 3) = nan;
  expect_throw_naming([&] { filter.Update(z); }, "covariance");
  z.covariance = Matrix6d::Identity();
  z.covariance(2, 2) = -1.0;
  expect_throw_naming([&] { filter.Update(z); }, "positive definite");
  z.covariance = Matrix6d::Identity();
  z.q_WX.coeffs() << 0.0, 0.0, 0.0, 2.0;
  expect_throw_naming([&] { filter.Update(z); }, "q_WX");

  // State untouched by the rejected inputs.
  EXPECT_TRUE(filter.Estimate().state.IsValid());
  EXPECT_DOUBLE_EQ(filter.time_s(), 0.01);

  control::QuadState bad;
  bad.v_W.y() = nan;
  expect_throw_naming([&] { PoseImuFilter f(PoseImuFilterParams{}, bad); }, "v_W");
  PoseImuFilterParams params;
  params.accel_noise_density = -1.0;
  expect_throw_naming([&] { PoseImuFilter f(params, control::QuadState{}); },
                      "accel_noise_density");
}

}  // namespace
}  // namespace aperture::perception
