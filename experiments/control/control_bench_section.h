#pragma once
// One comparison of `aperture bench control` (issue 4; thesis F.6, G.6, B.4 analogs). Each
// section flies its SITL experiments on the bench vehicle, writes its figures under its own key
// of `summary` (SI units) and adds its plots to `report`. The controllers model the nominal
// vehicle (control::VehicleParameters defaults: rotor drag d_x = 0.5, d_y = 0.35 1/s, asymmetric
// motor lag and kappa(f) of G.6.1); with vehicle.mismatch (the default, issue 21) the simulated
// vehicle departs from it by a sim::VehicleMismatch drawn from the flight's seed: options.seed
// for every tracking and hover flight (one bench vehicle), the throw's seed for each throw.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "output/html_report.h"
#include "sim/sitl/recovery_flight.h"
#include "sim/sitl/tracking_flight.h"
#include "sim/sitl/vehicle_mismatch.h"

namespace aperture::experiments {

struct ControlBenchOptions {
  std::uint64_t seed = 1;     // every random stream of every section derives from it
  int recovery_trials = 100;  // random throws of the recovery section (B.4)
  // Shorter flights and fewer trials with the same code paths: for tests and quick looks.
  bool quick = false;
  // The bench vehicle and its control stack (`--config`/`--set` sections control, dynamics, imu,
  // range): every flight of every section starts from these and changes only what its comparison
  // varies (the drag switch, the body-rate law, the mixing, the saturation, the thrust limits).
  sim::ControlStackParams control;
  sim::QuadrotorDynamicsParams dynamics;
  sim::ImuSensorParams imu;
  sim::RangeSensorParams range;  // the throws' height sensor (recovery section)
  // `--config`/`--set` section `vehicle`: mismatch on by default (false: vehicle = model).
  sim::VehicleMismatchParams vehicle{true, {}};
};

// A tracking flight of the bench vehicle and control stack (reference, duration and error window
// are the section's), every random stream from options.seed.
sim::TrackingFlightParams BenchTrackingFlight(const ControlBenchOptions& options);
// A throw of the bench vehicle and control stack (the throw and the seed are the section's).
sim::RecoveryFlightParams BenchRecoveryFlight(const ControlBenchOptions& options);

struct ControlBenchSection {
  std::string key;  // summary key, e.g. "drag", "mixer"
  std::function<void(const ControlBenchOptions&, nlohmann::json* summary,
                     output::HtmlReport* report)>
      run;
};

}  // namespace aperture::experiments
