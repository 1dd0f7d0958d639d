// GyroIntegrator against analytic rotations: a constant rate, a rate linear in time about a fixed
// axis (the trapezoid is exact for it), the held rate between and before samples, bad samples.
#include "perception/estimation/gyro_integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/so3.h"

namespace aperture::perception {
namespace {

ImuSample Gyro(double t_s, const Eigen::Vector3d& omega_B) {
  ImuSample sample;
  sample.t_s = t_s;
  sample.omega_B = omega_B;
  return sample;
}

TEST(GyroIntegratorTest, ConstantRateGivesTheExponential) {
  GyroIntegrator gyro;
  EXPECT_FALSE(gyro.OrientationAt(0.0).has_value());  // nothing yet
  const Eigen::Vector3d omega_B(0.3, -1.2, 0.7);
  for (int i = 0; i <= 200; ++i) gyro.Add(Gyro(1.0 + 0.005 * i, omega_B));
  // At the last sample and 13 ms past it (the rate held).
  EXPECT_TRUE(gyro.OrientationAt(2.0)->isApprox(control::ExpSo3(omega_B * 1.0), 1e-12));
  EXPECT_TRUE(gyro.OrientationAt(2.013)->isApprox(control::ExpSo3(omega_B * 1.013), 1e-12));
  EXPECT_TRUE(gyro.OrientationAt(1.998)->isApprox(control::ExpSo3(omega_B * 0.998), 1e-12));
  EXPECT_FALSE(gyro.OrientationAt(0.9).has_value());  // before the first sample
}

TEST(GyroIntegratorTest, RateLinearInTimeAboutAFixedAxis) {
  // omega(t) = (a + b t) n: angle(t) = a t + b t^2 / 2, irregular sample spacing.
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, 2.0, -2.0).normalized();
  const double a = 0.5, b = 3.0;
  std::vector<double> times_s;
  double t_s = 0.2;
  for (int i = 0; i < 100; ++i, t_s += (i % 3 == 0) ? 0.004 : 0.0055) times_s.push_back(t_s);
  GyroIntegrator gyro;
  for (double t : times_s) gyro.Add(Gyro(t, (a + b * t) * n));
  const double t0 = times_s.front(), t1 = times_s.back();
  const double angle = a * (t1 - t0) + 0.5 * b * (t1 * t1 - t0 * t0);
  EXPECT_TRUE(gyro.OrientationAt(t1)->isApprox(control::ExpSo3(angle * n), 1e-12));
}

TEST(GyroIntegratorTest, RejectsNonFiniteAndOutOfOrderSamples) {
  GyroIntegrator gyro;
  gyro.Add(Gyro(1.0, Eigen::Vector3d::Zero()));
  EXPECT_THROW(gyro.Add(Gyro(1.0, Eigen::Vector3d::Zero())), std::invalid_argument);
  EXPECT_THROW(gyro.Add(Gyro(0.5, Eigen::Vector3d::Zero())), std::invalid_argument);
  EXPECT_THROW(gyro.Add(Gyro(2.0, Eigen::Vector3d(NAN, 0.0, 0.0))), std::invalid_argument);
  EXPECT_THROW(gyro.Add(Gyro(NAN, Eigen::Vector3d::Zero())), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::perception
