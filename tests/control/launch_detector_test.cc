#include "control/launch_detector.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>

#include "control/constants.h"

namespace aperture::control {
namespace {

constexpr double kLaunchImuDt_s = 0.002;  // 500 Hz IMU
constexpr double kNoise = 0.3;  // m/s^2 per sample: accelerometer noise plus rotor-idle vibration

class NoisyAccel {
 public:
  explicit NoisyAccel(unsigned seed) : rng_(seed) {}
  // Specific force of a body with attitude q_WB and acceleration a_W: R^T (a + g z_W) + noise.
  Eigen::Vector3d Measure(const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& a_W) {
    return q_WB.conjugate() * (a_W + kGravity_mps2 * Eigen::Vector3d::UnitZ()) +
           kNoise * Eigen::Vector3d(normal_(rng_), normal_(rng_), normal_(rng_));
  }

 private:
  std::mt19937 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

TEST(LaunchDetector, IdleThrustFromVehicle) {
  const VehicleParameters vehicle;
  const LaunchDetectorParams params = LaunchDetectorParams::FromVehicle(vehicle);
  EXPECT_NEAR(params.idle_thrust_mps2, 4.0 * vehicle.rotor.MinThrust() / vehicle.mass_kg, 1e-12);
  EXPECT_NEAR(params.idle_thrust_mps2, LaunchDetectorParams().idle_thrust_mps2, 1e-9);
  EXPECT_DOUBLE_EQ(params.threshold_mps2, 2.0);  // t_launch of (B.29)
  EXPECT_DOUBLE_EQ(params.window_s, 0.05);       // 50 ms (B.29)
}

TEST(LaunchDetector, QuietAtRestAndInHover) {
  LaunchDetector detector;
  NoisyAccel accel(1);
  const Eigen::Quaterniond tilted(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()));
  for (int k = 0; k < 2000; ++k) {
    // On the ground level, then hovering tilted (hover: a = 0 whatever the attitude).
    const Eigen::Quaterniond q = k < 1000 ? Eigen::Quaterniond::Identity() : tilted;
    EXPECT_FALSE(detector.AddSample(k * kLaunchImuDt_s, accel.Measure(q, Eigen::Vector3d::Zero())));
  }
  EXPECT_NEAR(detector.MeanAccelNorm(), kGravity_mps2, 0.1);
}

TEST(LaunchDetector, QuietWhenShakenByHand) {
  // Vigorous shaking: 6 m/s^2 vertical and 6 m/s^2 lateral at 3 Hz while rocking +-0.5 rad. The
  // norm dips to g - 6 = 3.8 m/s^2 for an instant; averaged over 50 ms (0.15 period) it stays
  // above 9.81 - 6 sin(0.15 pi) / (0.15 pi) = 4.1 m/s^2, well over |c_idle| + t_launch = 2.44.
  LaunchDetector detector;
  NoisyAccel accel(2);
  double min_mean = 1e9;
  for (int k = 0; k < 2000; ++k) {
    const double t = k * kLaunchImuDt_s;
    const double phase = 2.0 * kPi * 3.0 * t;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.5 * std::sin(phase), Eigen::Vector3d::UnitY()));
    const Eigen::Vector3d a_W(6.0 * std::cos(phase), 0.0, 6.0 * std::sin(phase));
    EXPECT_FALSE(detector.AddSample(t, accel.Measure(q, a_W))) << "t = " << t;
    if (t > 0.05) min_mean = std::min(min_mean, detector.MeanAccelNorm());
  }
  RecordProperty("min_window_mean_mps2", std::to_string(min_mean));
  // The vertical part alone gives the bound; the lateral part only adds to the norm (measured
  // 4.2 m/s^2). 0.1 m/s^2 allows for the averaged noise (0.3 / sqrt(25) = 0.06).
  EXPECT_GT(min_mean, kGravity_mps2 - 6.0 * std::sin(0.15 * kPi) / (0.15 * kPi) - 0.1);
  EXPECT_LT(min_mean, kGravity_mps2 - 6.0 * std::sin(0.15 * kPi) / (0.15 * kPi) + 0.5);
}

TEST(LaunchDetector, FiresOnFreeFallAfterThrow) {
  // Held still, pushed upwards at 15 m/s^2 for 0.15 s (a throw), then released: ballistic flight
  // tumbling at 10 rad/s, the accelerometer measures only the idle rotor thrust c_idle z_B.
  const LaunchDetectorParams params;
  LaunchDetector detector(params);
  NoisyAccel accel(3);
  const double t_release = 0.65;
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  double t = 0.0;
  for (int k = 0; t < 1.0; ++k) {
    t = k * kLaunchImuDt_s;
    Eigen::Vector3d f_B;
    if (t < 0.5) {
      f_B = accel.Measure(q, Eigen::Vector3d::Zero());
    } else if (t < t_release) {
      f_B = accel.Measure(q, Eigen::Vector3d(0.0, 0.0, 15.0));
    } else {
      q = q *
          Eigen::Quaterniond(Eigen::AngleAxisd(10.0 * kLaunchImuDt_s, Eigen::Vector3d::UnitX()));
      f_B = params.idle_thrust_mps2 * Eigen::Vector3d::UnitZ() +
            accel.Measure(q, -kGravity_mps2 * Eigen::Vector3d::UnitZ());  // free fall: a = -g z_W
    }
    const bool launched = detector.AddSample(t, f_B);
    EXPECT_EQ(launched, t >= detector.launch_time_s() && detector.launched());
    if (t < t_release) {
      ASSERT_FALSE(launched) << "t = " << t;
    }
  }
  ASSERT_TRUE(detector.launched());
  const double delay = detector.launch_time_s() - t_release;
  RecordProperty("detection_delay_s", std::to_string(delay));
  // The window mean p 0.44 + (1 - p) 24.8 (push) falls below 2.44 once the free-fall fraction
  // p > 0.918: 46 ms after release, within the 50 ms window.
  EXPECT_NEAR(delay, 0.046, 0.004);
  detector.Reset();
  EXPECT_FALSE(detector.launched());
}

TEST(LaunchDetector, NeedsAFullWindowBeforeFiring) {
  LaunchDetector detector;
  const Eigen::Vector3d free_fall = Eigen::Vector3d::Zero();
  for (int k = 0; k < 25; ++k)
    EXPECT_FALSE(detector.AddSample(k * kLaunchImuDt_s, free_fall));  // 48 ms
  EXPECT_TRUE(detector.AddSample(25 * kLaunchImuDt_s, free_fall));    // 50 ms
}

TEST(LaunchDetector, RejectsBadInput) {
  LaunchDetectorParams params;
  params.window_s = 0.0;
  EXPECT_THROW(LaunchDetector{params}, std::invalid_argument);
  LaunchDetector detector;
  detector.AddSample(1.0, Eigen::Vector3d::UnitZ());
  EXPECT_THROW(detector.AddSample(0.5, Eigen::Vector3d::UnitZ()), std::invalid_argument);
  EXPECT_THROW(detector.AddSample(2.0, Eigen::Vector3d(NAN, 0, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace aperture::control
