#pragma once
// Launch (throw) detection of Faessler thesis paper B, Section B.3.1, (B.29). At rest or in the
// hand the accelerometer measures |f| ~ g; once thrown, the vehicle is in free fall up to the
// rotor thrust, so it measures only the mass-normalized thrust, |f| ~ |c_idle|. A launch is
// declared when the mean norm over the last 50 ms drops below the idle thrust plus a margin:
//     mean_{last window} |f_B| < |c_idle| + t_launch,   t_launch = 2.0 m/s^2.          (B.29)
// The detector needs a full window of samples before it can fire, and latches (Reset() re-arms).
#include <deque>

#include <Eigen/Core>

#include "control/vehicle_parameters.h"

namespace aperture::control {

struct LaunchDetectorParams {
  double window_s = 0.05;            // averaging window (B.29 text)
  double threshold_mps2 = 2.0;       // t_launch (B.29 text)
  // |c_idle|: mass-normalized thrust of all rotors at idle. Default: 4 * 0.05 N / 0.45 kg, the
  // default VehicleParameters (see FromVehicle).
  double idle_thrust_mps2 = 4.0 * 0.05 / 0.45;

  // Idle thrust of `vehicle`: sum_i gamma_i f(u_min) / m.
  static LaunchDetectorParams FromVehicle(const VehicleParameters& vehicle);
  // Throws std::invalid_argument naming the field (window_s <= 0, negative threshold or idle
  // thrust, non-finite values).
  void Validate() const;
};

class LaunchDetector {
 public:
  explicit LaunchDetector(const LaunchDetectorParams& params = {});

  // One accelerometer sample (t_s strictly increasing, else std::invalid_argument). Returns
  // launched().
  bool AddSample(double t_s, const Eigen::Vector3d& specific_force_B);
  bool launched() const { return launched_; }
  // Time of the sample that triggered (B.29) [s]; meaningful once launched().
  double launch_time_s() const { return launch_time_s_; }
  // Mean |f_B| over the current window [m/s^2] (0 before any sample).
  double MeanAccelNorm() const;
  void Reset();

 private:
  struct Sample {
    double t_s;
    double norm_mps2;
  };
  LaunchDetectorParams params_;
  std::deque<Sample> window_;
  double sum_norm_ = 0.0;
  double first_t_s_ = 0.0;
  bool launched_ = false;
  double launch_time_s_ = 0.0;
};

}  // namespace aperture::control
