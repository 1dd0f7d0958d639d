// Pose fusion: the mapping of a front end's PoseObservation into the filter's measurement for a
// fixed target and for a fixed camera (poses and covariances against perturbations), the body
// pose a measurement implies, and the one start / restart policy.
#include "perception/estimation/pose_fusion.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "control/constants.h"
#include "control/so3.h"

namespace aperture::perception {
namespace {

using control::kGravity_mps2;

using ::testing::HasSubstr;

Eigen::Isometry3d RandomPose(std::mt19937_64* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Vector6d xi;
  for (int i = 0; i < 6; ++i) xi(i) = normal(*rng);
  return control::ExpSe3(xi);
}

// A small perturbation delta = [dt; dr] of T_CX in the observation's convention (p' = Exp(dr) p +
// dt, R' = Exp(dr) R) and the observation with covariance
// delta delta^T: the mapped covariance must then be r r^T for the residual r the perturbation
// causes in the filter's convention [p' - p (W); Log(R^T R') (measured frame)].
struct Perturbed {
  PoseObservation observation;
  Eigen::Isometry3d T_CX_perturbed;
};

Perturbed PerturbedObservation(PoseObservation::Fixed fixed, std::mt19937_64* rng,
                               const Vector6d& delta) {
  Perturbed p;
  p.observation.stream = "test";
  p.observation.fixed = fixed;
  p.observation.t_s = 1.5;
  p.observation.T_CX = RandomPose(rng);
  p.observation.covariance_CX = delta * delta.transpose();
  p.T_CX_perturbed = p.observation.T_CX;
  p.T_CX_perturbed.linear() = control::ExpSo3(delta.tail<3>()) * p.observation.T_CX.linear();
  p.T_CX_perturbed.translation() =
      control::ExpSo3(delta.tail<3>()) * p.observation.T_CX.translation() + delta.head<3>();
  return p;
}

Vector6d Residual(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_perturbed) {
  Vector6d r;
  r << T_perturbed.translation() - T.translation(),
      control::LogSo3(T.linear().transpose() * T_perturbed.linear());
  return r;
}

const Vector6d kDelta = (Vector6d() << 1e-4, -2e-4, 0.5e-4, 1e-4, 0.7e-4, -1.5e-4).finished();

// Both maps are exact to first order; the second-order remainder (|delta|^2 ~ 1e-8 times the
// entries' 1e-4) and rounding in Log stay below 1e-11, while a wrong block (R_CX for R_XC, a
// missing lever arm) is off by ~1e-8, the size of the entries.
constexpr double kCovarianceTolerance = 1e-11;

// A measurement of another frame O (an odometry's) in W: the pose composes with T_WO, the position
// noise turns with R_WO (a 90 deg yaw swaps its x and y variances), the rotation noise, in X,
// stays.
TEST(InWorldFrameTest, ComposesThePoseAndTurnsThePositionNoise) {
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_WO.translation() = Eigen::Vector3d(1.0, 2.0, 0.5);
  PoseMeasurement z_O;
  z_O.t_s = 3.0;
  z_O.p_WX = Eigen::Vector3d(1.0, 0.0, 0.0);
  z_O.q_WX = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  z_O.covariance = Matrix6d::Zero();
  z_O.covariance.diagonal() << 1e-4, 2e-4, 3e-4, 4e-6, 5e-6, 6e-6;
  const PoseMeasurement z_W = InWorldFrame(T_WO, z_O);
  EXPECT_EQ(z_W.t_s, 3.0);
  EXPECT_LT((z_W.p_WX - Eigen::Vector3d(1.0, 3.0, 0.5)).norm(), 1e-12);
  EXPECT_LT(z_W.q_WX.angularDistance(Eigen::Quaterniond(T_WO.linear()) * z_O.q_WX), 1e-12);
  Vector6d expected;
  expected << 2e-4, 1e-4, 3e-4, 4e-6, 5e-6, 6e-6;
  EXPECT_LT((z_W.covariance.diagonal() - expected).norm(), 1e-15);
  EXPECT_LT((z_W.covariance - Matrix6d(expected.asDiagonal())).norm(), 1e-15);
  Eigen::Isometry3d scaled = T_WO;
  scaled.linear() *= 2.0;
  EXPECT_THROW(InWorldFrame(scaled, z_O), std::invalid_argument);
}

TEST(ToPoseMeasurementTest, FixedCameraMeasuresTheTargetInTheWorld) {
  std::mt19937_64 rng(5);
  const PoseRig rig{RandomPose(&rng), RandomPose(&rng), 1.0};  // T_WC, T_BX
  const Perturbed p = PerturbedObservation(PoseObservation::Fixed::kCamera, &rng, kDelta);
  const PoseMeasurement z = ToPoseMeasurement(p.observation, rig);
  const Eigen::Isometry3d T_WX = rig.T_W_fixed * p.observation.T_CX;
  const Vector6d r = Residual(T_WX, rig.T_W_fixed * p.T_CX_perturbed);
  EXPECT_LT((z.covariance - r * r.transpose()).cwiseAbs().maxCoeff(), kCovarianceTolerance);
  EXPECT_EQ(z.t_s, 1.5);
  EXPECT_TRUE(z.p_WX.isApprox(T_WX.translation(), 1e-12));
  EXPECT_TRUE(z.q_WX.toRotationMatrix().isApprox(T_WX.linear(), 1e-12));
  EXPECT_TRUE(z.p_BX.isApprox(rig.T_B_moving.translation(), 1e-12));
  EXPECT_TRUE(z.q_BX.toRotationMatrix().isApprox(rig.T_B_moving.linear(), 1e-12));
}

TEST(ToPoseMeasurementTest, FixedTargetMeasuresTheCameraInTheWorld) {
  std::mt19937_64 rng(6);
  const PoseRig rig{RandomPose(&rng), RandomPose(&rng), 1.0};  // T_WX, T_BC
  const Perturbed p = PerturbedObservation(PoseObservation::Fixed::kTarget, &rng, kDelta);
  const PoseMeasurement z = ToPoseMeasurement(p.observation, rig);
  const Eigen::Isometry3d T_WC = rig.T_W_fixed * p.observation.T_CX.inverse();
  const Vector6d r = Residual(T_WC, rig.T_W_fixed * p.T_CX_perturbed.inverse());
  EXPECT_LT((z.covariance - r * r.transpose()).cwiseAbs().maxCoeff(), kCovarianceTolerance);
  EXPECT_TRUE(z.p_WX.isApprox(T_WC.translation(), 1e-12));
  EXPECT_TRUE(z.q_WX.toRotationMatrix().isApprox(T_WC.linear(), 1e-12));
  EXPECT_TRUE(z.p_BX.isApprox(rig.T_B_moving.translation(), 1e-12));
  // The rig's scale multiplies the whole covariance.
  const PoseRig scaled{rig.T_W_fixed, rig.T_B_moving, 9.0};
  EXPECT_TRUE(ToPoseMeasurement(p.observation, scaled).covariance.isApprox(9.0 * z.covariance));
}

TEST(ToPoseMeasurementTest, BodyPoseMakesEveryTargetPointLandWhereTheCameraSeesIt) {
  // p_W of a target point through the body (T_WB T_BX p_X) equals the camera's view
  // (T_WC T_CX p_X): checks the composition order and the inverse of the extrinsics.
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    PoseObservation observation;
    observation.fixed = PoseObservation::Fixed::kCamera;
    observation.T_CX = RandomPose(&rng);
    observation.covariance_CX = Matrix6d::Identity();
    const PoseRig rig{RandomPose(&rng), RandomPose(&rng), 1.0};
    const PoseMeasurement z = ToPoseMeasurement(observation, rig);
    const Eigen::Vector3d p_X(0.1, -0.05, 0.02);
    const Eigen::Vector3d through_body =
        BodyOrientation(z) * (rig.T_B_moving * p_X) + BodyPosition(z);
    EXPECT_TRUE(through_body.isApprox(rig.T_W_fixed * (observation.T_CX * p_X), 1e-9));
  }
}

TEST(ToPoseMeasurementTest, RejectsNonRigidTransformsAndMissingCovariancesNamingThem) {
  PoseObservation observation;
  observation.stream = "led";
  observation.covariance_CX = Matrix6d::Identity();
  PoseRig rig;
  rig.T_W_fixed.linear() *= 1.01;
  try {
    ToPoseMeasurement(observation, rig);
    FAIL() << "a scaled T_W_fixed was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("T_W_fixed"));
  }
  rig = PoseRig{};
  rig.T_B_moving.linear()(2, 2) = -1.0;  // a reflection
  EXPECT_THROW(ToPoseMeasurement(observation, rig), std::invalid_argument);
  rig = PoseRig{};
  observation.covariance_CX.reset();
  try {
    ToPoseMeasurement(observation, rig);
    FAIL() << "an observation without covariance was fused";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("'led'"));
  }
  observation.covariance_CX = Matrix6d::Identity() * std::nan("");
  EXPECT_THROW(ToPoseMeasurement(observation, rig), std::invalid_argument);
  observation.covariance_CX = Matrix6d::Identity();
  rig.covariance_scale = 0.0;
  EXPECT_THROW(ToPoseMeasurement(observation, rig), std::invalid_argument);
}

ImuSample RestingImu(double t_s) {
  ImuSample sample;
  sample.t_s = t_s;
  sample.specific_force_B = Eigen::Vector3d(0.0, 0.0, kGravity_mps2);
  return sample;
}

PoseMeasurement PoseOfBodyAt(double t_s, const Eigen::Vector3d& p_WB) {
  PoseMeasurement z;
  z.t_s = t_s;
  z.p_WX = p_WB;
  z.covariance = Matrix6d::Identity() * 1e-6;  // 1 mm, 1 mrad
  return z;
}

// 24 ms of resting IMU after *t_s, then the pose `pose_at` gives for the new time *t_s + 24 ms.
template <typename PoseAt>
std::vector<PoseFusionOutcome> AdvanceAtRest(PoseFusion& fusion, double* t_s, PoseAt pose_at) {
  for (int i = 1; i <= 12; ++i) fusion.AddImu(RestingImu(*t_s + 0.002 * i));
  *t_s += 0.024;
  return fusion.AddPose(pose_at(*t_s));
}

// Ten poses of a body resting at p_WB, 24 ms apart: the filter started and fusing. Returns the
// time.
double RestAt(PoseFusion& fusion, const Eigen::Vector3d& p_WB) {
  double t_s = 0.0;
  for (int k = 0; k < 10; ++k) {
    AdvanceAtRest(fusion, &t_s, [&](double t) { return PoseOfBodyAt(t, p_WB); });
  }
  return t_s;
}

TEST(PoseFusionTest, AMeasurementAheadOfTheImuWaitsForIt) {
  PoseFusion fusion(PoseFusionParams{});
  for (int k = 1; k <= 10; ++k) fusion.AddImu(RestingImu(0.002 * k));
  ASSERT_EQ(fusion.AddPose(PoseOfBodyAt(0.02, Eigen::Vector3d(0, 0, 1))).size(), 1u);  // start
  // Stamped 4 ms after the latest IMU sample: nothing happens until the IMU gets there.
  EXPECT_TRUE(fusion.AddPose(PoseOfBodyAt(0.024, Eigen::Vector3d(0, 0, 1))).empty());
  fusion.AddImu(RestingImu(0.022));
  EXPECT_EQ(fusion.counts().applied, 0);
  fusion.AddImu(RestingImu(0.024));
  EXPECT_EQ(fusion.counts().applied, 1);
  EXPECT_DOUBLE_EQ(fusion.last_pose_t_s(), 0.024);
}

TEST(PoseFusionTest, RestartsAfterConsecutiveOutliersWithTheVelocityOfTheRejectedRun) {
  PoseFusionParams params;
  params.max_consecutive_rejections = 3;
  PoseFusion fusion(params);
  const Eigen::Vector3d p_set(0.0, 0.0, 2.0);
  double t_s = RestAt(fusion, p_set);
  EXPECT_EQ(fusion.counts().starts, 1);
  EXPECT_EQ(fusion.counts().applied, 9);
  // The pose source jumps by 0.5 m and moves on at 1 m/s (the vehicle was pushed and the IMU
  // missed the impulse): far outside the gate, so the first two are rejected, then the filter
  // restarts there with the velocity of the rejected poses.
  const double t_jump = t_s;
  const auto pushed = [&](double t) {
    return Eigen::Vector3d(p_set + Eigen::Vector3d(0.5 + 1.0 * (t - t_jump), 0.0, 0.0));
  };
  const auto pushed_pose = [&](double t) { return PoseOfBodyAt(t, pushed(t)); };
  for (int k = 1; k < params.max_consecutive_rejections; ++k) {
    const std::vector<PoseFusionOutcome> outcomes = AdvanceAtRest(fusion, &t_s, pushed_pose);
    ASSERT_EQ(outcomes.size(), 1u);
    EXPECT_FALSE(outcomes[0].started_filter);
    EXPECT_EQ(outcomes[0].update.status, PoseUpdateStatus::kRejectedOutlier);
  }
  const std::vector<PoseFusionOutcome> restart = AdvanceAtRest(fusion, &t_s, pushed_pose);
  ASSERT_EQ(restart.size(), 1u);
  EXPECT_TRUE(restart[0].started_filter);
  EXPECT_EQ(fusion.counts().starts, 2);
  EXPECT_EQ(fusion.counts().restarts, 1);
  // Noise-free poses: position and velocity exact up to rounding.
  EXPECT_LT((fusion.estimate()->state.p_WB - pushed(t_s)).norm(), 1e-6);
  EXPECT_LT((fusion.estimate()->state.v_W - Eigen::Vector3d(1.0, 0.0, 0.0)).norm(), 1e-6);
}

// A run of noisy poses (2 cm, as a visual odometry's) jumped 0.5 m away but not moving: the
// endpoints would say 0.83 m/s, the least-squares fit's standard error is 0.59 m/s, so the restart
// keeps the previous (resting) velocity.
TEST(PoseFusionTest, RestartKeepsThePreviousVelocityWhenTheRunDoesNotResolveADifferentOne) {
  PoseFusionParams params;
  params.max_consecutive_rejections = 3;
  PoseFusion fusion(params);
  const Eigen::Vector3d p_set(0.0, 0.0, 2.0);
  double t_s = RestAt(fusion, p_set);
  for (const double noise_m : {-0.02, 0.0, 0.02}) {
    AdvanceAtRest(fusion, &t_s, [&](double t) {
      PoseMeasurement z = PoseOfBodyAt(t, p_set + Eigen::Vector3d(0.5, noise_m, 0.0));
      z.covariance.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() * 4e-4;
      return z;
    });
  }
  ASSERT_EQ(fusion.counts().restarts, 1);
  EXPECT_LT(fusion.estimate()->state.v_W.norm(), 0.05) << fusion.estimate()->state.v_W.transpose();
}

TEST(PoseFusionTest, RefusesARestartThatWouldTurnTheBodyAwayFromItsGyroAttitude) {
  const Eigen::Vector3d p_set(0.0, 0.0, 2.0);
  // A pattern seen the other way round: the body turned by 180 deg about z and moved by 0.5 m.
  const auto turned = [&](double t) {
    PoseMeasurement z = PoseOfBodyAt(t, p_set + Eigen::Vector3d(0.5, 0.0, 0.0));
    z.q_WX = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
    return z;
  };
  const auto at_set = [&](double t) { return PoseOfBodyAt(t, p_set); };
  // 10 true poses, then `turned_poses` turned ones, 24 ms apart with resting IMU in between.
  const auto fly = [&](PoseFusion& fusion, int turned_poses) {
    double t_s = RestAt(fusion, p_set);
    for (int k = 0; k < turned_poses; ++k) AdvanceAtRest(fusion, &t_s, turned);
    return t_s;
  };
  PoseFusionParams params;
  params.max_consecutive_rejections = 3;
  PoseFusion fusion(params);
  // Two full runs of rejections, consistently turned: neither restarts the filter.
  double t_s = fly(fusion, 2 * params.max_consecutive_rejections);
  EXPECT_EQ(fusion.counts().restarts, 0);
  EXPECT_EQ(fusion.counts().restarts_refused, 2);
  EXPECT_LT(fusion.estimate()->state.q_WB.angularDistance(Eigen::Quaterniond::Identity()), 1e-3);
  // The true pose again: fused.
  const std::vector<PoseFusionOutcome> back = AdvanceAtRest(fusion, &t_s, at_set);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_TRUE(back[0].update.applied());
  // With the limit off, one run restarts the filter on the turned pose.
  params.max_restart_rotation_rad = M_PI;
  PoseFusion unlimited(params);
  fly(unlimited, params.max_consecutive_rejections);
  EXPECT_EQ(unlimited.counts().restarts, 1);
  EXPECT_NEAR(unlimited.estimate()->state.q_WB.angularDistance(Eigen::Quaterniond::Identity()),
              M_PI, 1e-3);
}

// A resting body whose accelerometer is `noise_factor` times noisier than the filter's
// specification, seen by 1 cm / 10 mrad poses every 24 ms for 6 s. Returns the measurements the
// filter gated out.
int RejectionsWithAnImuNoisierThanSpecified(PoseFusion& fusion, double noise_factor) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double rate_hz = 500.0;
  const double accel_sigma =
      noise_factor * fusion.params().filter.accel_noise_density * std::sqrt(rate_hz);
  double t_s = 0.0;
  for (int k = 0; k < 250; ++k) {
    for (int i = 1; i <= 12; ++i) {
      ImuSample sample = RestingImu(t_s + i / rate_hz);
      for (int axis = 0; axis < 3; ++axis) {
        sample.specific_force_B(axis) += accel_sigma * normal(rng);
      }
      fusion.AddImu(sample);
    }
    t_s += 12 / rate_hz;
    PoseMeasurement z = PoseOfBodyAt(
        t_s, Eigen::Vector3d(0.01 * normal(rng), 0.01 * normal(rng), 2.0 + 0.01 * normal(rng)));
    z.q_WX = control::ExpQuaternion(0.01 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
    z.covariance = Matrix6d::Identity() * 1e-4;
    fusion.AddPose(z);
  }
  return fusion.counts().rejected_outlier;
}

TEST(PoseFusionTest, AdaptsItsProcessNoiseToAnImuNoisierThanSpecified) {
  // The specification's accelerometer (3.9e-3 m/s^2/sqrt(Hz)) drifts ~0.2 mm between poses; thirty
  // times that wanders several centimetres over a second of 1 cm poses the filter over-trusts.
  PoseFusion fixed(PoseFusionParams{});
  PoseFusion adapting(PoseFusionParams{});
  adapting.AdaptProcessNoise(1000.0);
  const int rejected_fixed = RejectionsWithAnImuNoisierThanSpecified(fixed, 30.0);
  const int rejected_adapting = RejectionsWithAnImuNoisierThanSpecified(adapting, 30.0);
  EXPECT_DOUBLE_EQ(fixed.process_noise_scale(), 1.0);
  EXPECT_GT(adapting.process_noise_scale(), 30.0);  // densities x30 are variances x900
  EXPECT_LT(rejected_adapting, rejected_fixed / 2) << rejected_fixed;
  EXPECT_LT(adapting.counts().restarts, fixed.counts().restarts + 1);

  // An IMU as specified leaves the scale within a few of 1 (the residuals match their covariance;
  // bounded below by 1, the scale's random walk on the noisy mean wanders a little above it).
  PoseFusion consistent(PoseFusionParams{});
  consistent.AdaptProcessNoise(1000.0);
  RejectionsWithAnImuNoisierThanSpecified(consistent, 1.0);
  EXPECT_LT(consistent.process_noise_scale(), 10.0);
  EXPECT_LT(consistent.process_noise_scale() * 20.0, adapting.process_noise_scale());

  EXPECT_THROW(consistent.AdaptProcessNoise(0.5), std::invalid_argument);
  EXPECT_THROW(consistent.AdaptProcessNoise(std::nan("")), std::invalid_argument);
}

TEST(PoseFusionTest, ExplicitStartReplaysTheBufferedImu) {
  PoseFusion fusion(PoseFusionParams{});
  for (int k = 1; k <= 50; ++k) fusion.AddImu(RestingImu(0.002 * k));
  control::QuadState state;
  state.t_s = 0.05;
  state.p_WB = Eigen::Vector3d(1.0, 2.0, 3.0);
  fusion.Start(state);
  ASSERT_TRUE(fusion.started());
  EXPECT_NEAR(fusion.estimate()->state.t_s, 0.1, 1e-12);  // replayed to the latest sample
  EXPECT_LT((fusion.estimate()->state.p_WB - state.p_WB).norm(), 1e-9);  // at rest
  EXPECT_THROW(PoseFusion(PoseFusionParams{{}, 0}), std::invalid_argument);
}

// Heights: dropped before the start, held until the IMU reaches their time, fused without
// touching x, y; one far off is gated and counted, and never restarts the filter.
TEST(PoseFusionTest, FusesHeightsOnceTheImuHasReachedThem) {
  PoseFusion fusion(PoseFusionParams{});
  fusion.AddHeight({0.0, 1.0, 4e-4});  // before the start: dropped
  const Eigen::Vector3d p_WB(1.0, 2.0, 3.0);
  double t_s = RestAt(fusion, p_WB);
  EXPECT_EQ(fusion.counts().heights_applied, 0);
  fusion.AddHeight({t_s + 0.004, 3.02, 4e-4});  // 2 cm above the poses, ahead of the IMU
  EXPECT_EQ(fusion.counts().heights_applied, 0);
  fusion.AddImu(RestingImu(t_s + 0.002));
  EXPECT_EQ(fusion.counts().heights_applied, 0);
  fusion.AddImu(RestingImu(t_s + 0.004));
  EXPECT_EQ(fusion.counts().heights_applied, 1);
  EXPECT_GT(fusion.estimate()->state.p_WB.z(), 3.0);  // pulled up
  EXPECT_LT((fusion.estimate()->state.p_WB.head<2>() - p_WB.head<2>()).norm(), 1e-6);
  fusion.AddHeight({t_s + 0.004, 4.0, 4e-4});  // 1 m off
  EXPECT_EQ(fusion.counts().heights_rejected, 1);
  EXPECT_EQ(fusion.counts().restarts, 0);
  EXPECT_THROW(fusion.AddHeight({t_s, std::nan(""), 4e-4}), std::invalid_argument);
  EXPECT_THROW(fusion.AddHeight({t_s, 3.0, 0.0}), std::invalid_argument);
}

// Starting again from an estimate of the past (the gap mission's odometry alignment): its
// biases, velocity and widened covariance are the filter's, the IMU since is replayed, and the
// fused poses after it correct the velocity. An estimate older than the IMU buffer is refused.
TEST(PoseFusionTest, StartsAgainFromAnEstimateWithItsCovariance) {
  PoseFusion fusion(PoseFusionParams{});
  const Eigen::Vector3d p_WB(1.0, 2.0, 3.0);
  double t_s = RestAt(fusion, p_WB);
  PoseImuEstimate past = *fusion.estimate();
  AdvanceAtRest(fusion, &t_s, [&](double t) { return PoseOfBodyAt(t, p_WB); });
  const int starts = fusion.counts().starts;
  past.state.v_W = Eigen::Vector3d(0.3, 0.0, 0.0);  // wrong, and known to be uncertain
  past.accel_bias_B = Eigen::Vector3d(0.0, 0.0, 0.01);
  past.covariance.block<3, 3>(ErrorStateIndex::kVelocity, ErrorStateIndex::kVelocity) +=
      0.25 * Eigen::Matrix3d::Identity();
  fusion.Start(past);
  EXPECT_EQ(fusion.counts().starts, starts + 1);
  EXPECT_DOUBLE_EQ(fusion.estimate()->state.t_s, t_s);  // replayed to the latest IMU sample
  EXPECT_EQ(fusion.estimate()->accel_bias_B, past.accel_bias_B);
  EXPECT_GT(fusion.estimate()->covariance(ErrorStateIndex::kVelocity, ErrorStateIndex::kVelocity),
            0.25);
  // 24 ms of replay at 0.3 m/s (the bias, 0.01 m/s^2 along gravity, adds < 0.01 mm).
  EXPECT_NEAR(fusion.estimate()->state.p_WB.x() - past.state.p_WB.x(), 0.3 * 0.024, 1e-4);
  for (int k = 0; k < 10; ++k) {
    AdvanceAtRest(fusion, &t_s, [&](double t) { return PoseOfBodyAt(t, p_WB); });
  }
  EXPECT_EQ(fusion.counts().restarts, 0);  // the poses were fused, not gated out
  EXPECT_LT(fusion.estimate()->state.v_W.norm(), 0.03) << fusion.estimate()->state.v_W;

  for (int k = 1; k <= 300; ++k) fusion.AddImu(RestingImu(t_s + 0.002 * k));  // 0.6 s more
  try {
    fusion.Start(past);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("history_duration_s"));
  }
}

}  // namespace
}  // namespace aperture::perception
