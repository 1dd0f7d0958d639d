#include "experiments/control/control_bench_section.h"

namespace aperture::experiments {

sim::TrackingFlightParams BenchTrackingFlight(const ControlBenchOptions& options) {
  sim::TrackingFlightParams params;
  params.control = options.control;
  params.dynamics = options.dynamics;
  params.imu = options.imu;
  params.vehicle = options.vehicle;
  params.seed = options.seed;
  return params;
}

sim::RecoveryFlightParams BenchRecoveryFlight(const ControlBenchOptions& options) {
  sim::RecoveryFlightParams params;
  params.control = options.control;
  params.dynamics = options.dynamics;
  params.imu = options.imu;
  params.range = options.range;
  params.vehicle = options.vehicle;
  return params;
}

}  // namespace aperture::experiments
