#include "sim/sensors/imu_sensor.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "sim/vehicle/quadrotor_dynamics.h"

namespace aperture::sim {
namespace {

ImuSensorParams NoiselessImu() {
  ImuSensorParams params;
  params.accel_noise_density = 0.0;
  params.gyro_noise_density = 0.0;
  params.accel_bias_random_walk = 0.0;
  params.gyro_bias_random_walk = 0.0;
  params.latency_s = 0.0;
  return params;
}

// Runs the vehicle for duration_s at 1 ms steps and collects the IMU output.
std::vector<perception::ImuSample> Fly(QuadrotorDynamics* vehicle, ImuSensor* imu, double duration_s) {
  std::vector<perception::ImuSample> samples;
  const int steps = static_cast<int>(std::lround(duration_s / 0.001));
  for (int k = 0; k < steps; ++k) {
    vehicle->Step(0.001);
    for (const auto& s : imu->Update(vehicle->state().t_s, vehicle->SpecificForce_B(),
                                     vehicle->state().omega_B)) {
      samples.push_back(s);
    }
  }
  return samples;
}

TEST(ImuSensorTest, ReadsPlusGAlongBodyZInHover) {
  QuadrotorDynamicsParams params;
  QuadrotorDynamics vehicle(params);
  control::RotorThrustCommand hover;
  hover.thrust_N.setConstant(params.vehicle.mass_kg * params.vehicle.gravity_mps2 / 4.0);
  vehicle.SetRotorThrustCommand(hover);
  vehicle.SettleRotors();
  ImuSensor imu(NoiselessImu());
  const auto samples = Fly(&vehicle, &imu, 1.0);
  ASSERT_EQ(samples.size(), 500u);  // 500 Hz over 1 s of 1 ms steps
  for (const auto& s : samples) {
    EXPECT_TRUE(s.specific_force_B.isApprox(Eigen::Vector3d(0, 0, params.vehicle.gravity_mps2), 1e-12));
    EXPECT_NEAR(s.omega_B.norm(), 0.0, 1e-12);
  }
}

TEST(ImuSensorTest, ReadsZeroInFreeFall) {
  QuadrotorDynamicsParams params;
  params.vehicle.rotor.thrust_coeffs_N = Eigen::Vector3d(0.8, 1.6, 0.8);  // f(-1) = 0
  params.vehicle.rotor_drag_D_per_s.setZero();
  control::QuadState initial;
  initial.omega_B = Eigen::Vector3d(0.0, 0.0, 1.0);
  QuadrotorDynamics vehicle(params, initial);
  ImuSensor imu(NoiselessImu());
  for (const auto& s : Fly(&vehicle, &imu, 1.0)) {
    EXPECT_NEAR(s.specific_force_B.norm(), 0.0, 1e-12);
    EXPECT_NEAR(s.omega_B.z(), 1.0, 1e-9);  // yaw drag torques cancel at equal commands
  }
  EXPECT_LT(vehicle.state().v_W.z(), -9.0);  // it did fall
}

TEST(ImuSensorTest, ReadsTheRotorDragMovingThroughTheAir) {
  // Motors off, omega = 0, a yawed and tilted attitude, moving through a steady wind: the only
  // non-gravitational force is the rotor drag of (F.2), so the accelerometer reads
  // -D R^T v_a. The airspeed in B follows v_aB' = -D v_aB - g R^T z_W exactly (constant R and
  // wind), so every sample is checked against that closed form, not against the code's formula.
  QuadrotorDynamicsParams params;
  params.vehicle.rotor.thrust_coeffs_N = Eigen::Vector3d(0.8, 1.6, 0.8);  // f(-1) = 0
  params.vehicle.rotor_drag_D_per_s = Eigen::Vector3d(0.6, 0.25, 0.1);
  control::QuadState initial;
  initial.q_WB = Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitZ()) *
                 Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) *
                 Eigen::AngleAxisd(-0.15, Eigen::Vector3d::UnitX());
  initial.v_W = Eigen::Vector3d(3.0, -2.0, 0.5);
  const Eigen::Vector3d wind_W(-1.0, 1.0, 0.0);
  QuadrotorDynamics vehicle(params, initial);
  vehicle.SetWindVelocity_W(wind_W);
  ImuSensor imu(NoiselessImu());
  const Eigen::Matrix3d R_WB = initial.q_WB.toRotationMatrix();
  const Eigen::Array3d d = params.vehicle.rotor_drag_D_per_s.array();
  const Eigen::Array3d g_B =
      (R_WB.transpose() * Eigen::Vector3d(0, 0, params.vehicle.gravity_mps2)).array();
  const Eigen::Array3d va0_B = (R_WB.transpose() * (initial.v_W - wind_W)).array();
  const auto samples = Fly(&vehicle, &imu, 0.5);
  ASSERT_EQ(samples.size(), 250u);
  for (const auto& s : samples) {
    const Eigen::Array3d va_B = (va0_B + g_B / d) * (-d * s.t_s).exp() - g_B / d;
    EXPECT_TRUE(s.specific_force_B.isApprox((-d * va_B).matrix(), 1e-9)) << "t = " << s.t_s;
  }
  // Airspeed ~1.8 m/s along +x_B and ~4.7 m/s along -y_B at the start: the drag pushes
  // along -x_B and +y_B.
  ASSERT_GT(va0_B.x(), 1.0);
  ASSERT_LT(va0_B.y(), -1.0);
  EXPECT_LT(samples.front().specific_force_B.x(), -0.5);
  EXPECT_GT(samples.front().specific_force_B.y(), 0.5);
}

TEST(ImuSensorTest, WhiteNoiseStdMatchesDensityTimesSqrtRate) {
  ImuSensorParams params = NoiselessImu();
  params.rate_hz = 1000.0;
  params.accel_noise_density = 4e-3;
  params.gyro_noise_density = 1e-4;
  ImuSensor imu(params);
  const int n = 20000;
  Eigen::Array3d sum_a = Eigen::Array3d::Zero(), sum_a2 = sum_a, sum_g = sum_a, sum_g2 = sum_a;
  for (int k = 0; k < n; ++k) {
    const auto out = imu.Update(k * 1e-3, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    ASSERT_EQ(out.size(), 1u);
    sum_a += out[0].specific_force_B.array();
    sum_a2 += out[0].specific_force_B.array().square();
    sum_g += out[0].omega_B.array();
    sum_g2 += out[0].omega_B.array().square();
  }
  const Eigen::Array3d std_a = (sum_a2 / n - (sum_a / n).square()).sqrt();
  const Eigen::Array3d std_g = (sum_g2 / n - (sum_g / n).square()).sqrt();
  // Relative std of a sample std from n draws is 1/sqrt(2n) = 0.5 %: 5 % is a 10-sigma bound.
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std_a[i] / (4e-3 * std::sqrt(1000.0)), 1.0, 0.05);
    EXPECT_NEAR(std_g[i] / (1e-4 * std::sqrt(1000.0)), 1.0, 0.05);
  }
}

TEST(ImuSensorTest, BiasRandomWalkVarianceGrowsLinearlyInTime) {
  const double sigma_b = 3e-3, rate_hz = 250.0;
  const int runs = 1000;
  const int k1 = 500, k2 = 1000;  // samples at 2 s and 4 s
  double sum_sq_1 = 0.0, sum_sq_2 = 0.0;
  for (int run = 0; run < runs; ++run) {
    ImuSensorParams params = NoiselessImu();
    params.rate_hz = rate_hz;
    params.accel_bias_random_walk = sigma_b;
    params.seed = 1000 + run;
    ImuSensor imu(params);
    for (int k = 0; k <= k2; ++k) {
      const auto out = imu.Update(k / rate_hz, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
      // With no white noise the output is the bias accumulated over k periods.
      if (k == k1) sum_sq_1 += out[0].specific_force_B.squaredNorm();
      if (k == k2) sum_sq_2 += out[0].specific_force_B.squaredNorm();
    }
  }
  const double var_1 = sum_sq_1 / (3.0 * runs), var_2 = sum_sq_2 / (3.0 * runs);
  // Var b(t) = sigma_b^2 t. 3000 draws: relative std of the variance sqrt(2/3000) = 2.6 %; 10 %
  // is a ~4-sigma bound.
  EXPECT_NEAR(var_1 / (sigma_b * sigma_b * k1 / rate_hz), 1.0, 0.1);
  EXPECT_NEAR(var_2 / (sigma_b * sigma_b * k2 / rate_hz), 1.0, 0.1);
}

TEST(ImuSensorTest, LatencyDelaysDeliveryAndKeepsMeasurementTime) {
  ImuSensorParams params = NoiselessImu();
  params.latency_s = 0.005;
  ImuSensor imu(params);
  int delivered = 0;
  for (int k = 1; k <= 100; ++k) {
    const double t = k * 1e-3;
    // True rate omega_x = t identifies when each sample was taken.
    for (const auto& s : imu.Update(t, Eigen::Vector3d::Zero(), Eigen::Vector3d(t, 0, 0))) {
      EXPECT_NEAR(s.t_s, t - 0.005, 1e-9);
      EXPECT_NEAR(s.omega_B.x(), s.t_s, 1e-12);
      ++delivered;
    }
  }
  // Samples taken at 1, 3, ..., 99 ms; those taken after 95 ms are still in flight.
  EXPECT_EQ(delivered, 48);
}

TEST(ImuSensorTest, StampAtDeliveryShiftsTimestampsByLatency) {
  ImuSensorParams params = NoiselessImu();
  params.latency_s = 0.004;
  params.stamp_at_delivery = true;
  ImuSensor imu(params);
  for (int k = 1; k <= 100; ++k) {
    const double t = k * 1e-3;
    for (const auto& s : imu.Update(t, Eigen::Vector3d::Zero(), Eigen::Vector3d(t, 0, 0))) {
      EXPECT_NEAR(s.t_s, t, 1e-12);
      EXPECT_NEAR(s.omega_B.x(), t - 0.004, 1e-9);  // data older than the stamp
    }
  }
}

TEST(ImuSensorTest, SameSeedGivesIdenticalSamplesOtherSeedDoesNot) {
  const auto run = [](std::uint64_t seed) {
    ImuSensorParams params;  // default noise and bias walk
    params.seed = seed;
    ImuSensor imu(params);
    std::vector<perception::ImuSample> out;
    for (int k = 0; k < 200; ++k) {
      for (const auto& s : imu.Update(k * 1e-3, Eigen::Vector3d(0, 0, 9.81), Eigen::Vector3d::Zero())) {
        out.push_back(s);
      }
    }
    return out;
  };
  const auto a = run(7), b = run(7), c = run(8);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].t_s, b[i].t_s);
    EXPECT_EQ(a[i].specific_force_B, b[i].specific_force_B);
    EXPECT_EQ(a[i].omega_B, b[i].omega_B);
  }
  EXPECT_NE(a[0].specific_force_B, c[0].specific_force_B);
}

TEST(ImuSensorTest, ValidateRejectsBadParameters) {
  ImuSensorParams params;
  params.rate_hz = 0.0;
  EXPECT_THROW(ImuSensor{params}, std::invalid_argument);
  params = ImuSensorParams();
  params.latency_s = -1e-3;
  try {
    params.Validate();
    FAIL() << "negative latency accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("latency_s"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace aperture::sim
