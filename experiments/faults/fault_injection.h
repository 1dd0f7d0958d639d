#pragma once
// The faults of `aperture bench faults` (issue 18 item 5), one at a time at a level. A fault is
// injected into the SITL after the mission was built on the nominal parameters, so the mission is
// not told of it: its filter keeps the nominal IMU specification, its flight controller the
// nominal vehicle, its latency compensation the nominal camera latency.
//
//   const FaultSpec& fault = FindFault("gust");
//   const FaultDraw draw = DrawFault(trial_seed);        // direction and onset, per trial
//   InjectFault(fault.kind, fault.DefaultLevel(), draw, &sitl);
//
// Levels: each fault is swept over the range [low, high] at kSweepFractions; its default
// level is the middle of the range and "twice the default" its top (exactly twice for the ranges
// that start at no fault; for the IMU noise x1-x10, twice the excess noise over nominal).
//   frame_drop         probability a camera frame is lost                0 - 0.5
//   camera_latency     every camera's delivery latency added [s]          0 - 0.1
//   imu_noise          IMU white-noise densities and bias walks x        1 - 10
//   accel_bias         accelerometer turn-on bias added, |b| [m/s^2]     0 - 0.3 (random direction)
//   gust               a 1 s wind gust, horizontal [m/s]                  0 - 5 (random direction)
//   motor_loss         one motor's thrust efficiency lost (1 - gamma_1)  0 - 0.3 (100 % - 70 %)
//   perception_outage  every camera blind for this long [s]               0 - 0.5
// The gust and the outage start at a drawn time in the first third of the flight (from 1 s on),
// where the missions detect, approach and hold (the gap mission crosses at ~6 s of its 15 s);
// the bias is there from the start.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/sitl/sitl_runner.h"

namespace aperture::experiments {

enum class FaultKind {
  kFrameDrop,
  kCameraLatency,
  kImuNoise,
  kAccelBias,
  kGust,
  kMotorLoss,
  kPerceptionOutage,
};

// Where in [low, high] the sweep's levels lie.
inline constexpr std::array<double, 5> kSweepFractions = {0.0, 0.25, 0.5, 0.75, 1.0};

struct FaultSpec {
  FaultKind kind;
  std::string name;   // "frame_drop", as on the command line and in summary.json
  std::string unit;   // of the level, e.g. "s", "m/s", "x" (a factor)
  std::string label;  // axis label of the report's plot
  double low = 0.0;   // the level without the fault
  double high = 0.0;  // the top of the range
  // Rounded to 1e-9 so that a level reads as it is written (0.225, not 0.22499999999999998).
  double LevelAt(double fraction) const;
  double DefaultLevel() const { return LevelAt(0.5); }
  double TwiceDefaultLevel() const { return high; }
  std::vector<double> SweepLevels() const;  // LevelAt(kSweepFractions)
};

// Every fault, in the order above.
const std::vector<FaultSpec>& FaultCatalogue();
// std::invalid_argument listing the known names for an unknown one.
const FaultSpec& FindFault(const std::string& name);

// A fault at a level as written on the command line: "NAME=LEVEL", e.g. "motor_loss=0.15"
// (aperture sim --fault). std::invalid_argument quoting the text for a missing '=', an unknown
// name (listing the known ones), or a level that is not a number in [low, high] of the fault.
struct FaultSetting {
  const FaultSpec* fault = nullptr;
  double level = 0.0;
};
FaultSetting ParseFaultSetting(const std::string& text);

// What a trial draws for its fault (a pure function of the seed): the gust's and the bias'
// direction and the onset of the gust and the outage as a fraction of their window.
struct FaultDraw {
  Eigen::Vector3d direction_unit = Eigen::Vector3d::UnitX();  // random on the sphere
  double heading_rad = 0.0;                                   // horizontal direction (gust)
  double onset_fraction = 0.0;                                // in [0, 1)
};
FaultDraw DrawFault(std::uint64_t seed);

// The onset of a gust or outage in a flight of `duration_s`: from 1 s to a third of the flight
// (1 s in flights of 3 s or less) [s].
double FaultOnsetS(const FaultDraw& draw, double duration_s);

// Changes `sitl` (a mission's parameters after the mission was built) by the fault at `level`.
// The level of no fault leaves it unchanged. motor_loss keeps the flight controller on the model
// it had (sets flight_controller_model to the nominal vehicle when unset) and lowers rotor 1's
// fitness gamma_1 of the simulated vehicle. Throws std::invalid_argument for a non-finite level
// or one outside [low, high] of the fault (a drop probability of 1 or more included).
void InjectFault(FaultKind kind, double level, const FaultDraw& draw, sim::SitlRunnerParams* sitl);

}  // namespace aperture::experiments
