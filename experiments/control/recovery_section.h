#pragma once
// The "recovery" section of `aperture bench control` (Faessler thesis paper B, B.3, B.4; issue 4):
// seeded random hand throws of the bench vehicle, each flown by sim::FlyRecoveryFlight: the
// on-board chain of paper B from simulated sensors alone (RecoveryAutopilot: launch detection
// (B.29), IMU attitude estimator (B.22)-(B.26), height filter (B.27), (B.28) on the range sensor,
// five-stage state machine (B.3.2), the vision pipeline's initialization emulated with its failure
// modes (sim/sitl/visual_initialization.h)) -> the simulated flight controller at 1 kHz (LQR body
// rates, iterative mixer, prioritized saturation) -> the bench vehicle (rotor drag, motor lag,
// default IMU noise).
//
// A throw (sim::SampleHandThrow; B.4.2: "maximum body rates above 650 deg/s, linear velocities
// exceeding 3.6 m/s", outdoors above 800 deg/s and 6 m/s), thrown by the hand in 0.25 s
// (sim::HandMotionAt) from a still hold; released at 1.5 m with a tilt of 0-180 deg (upside-down
// included), 0-4 m/s horizontally in a random direction, -1 to +4 m/s vertically (lobs released
// slightly downwards included) and 0-14 rad/s about a random axis.
//
// Success ("recovered"): no ground contact (body and propellers) and the position stage (5) held
// for 4 s within 10 s of the release. Keys: recovery.trials, recovery.successes,
// recovery.crashes, recovery.time_mean / time_max [s] (release -> position stage, successful
// throws), recovery.min_height [m] (lowest height of the centre over all throws),
// recovery.vision_not_initialized (failures without a vision estimate: B.4.2's failure mode),
// recovery.vision_time_mean [s], recovery.success_rate. Trials run in parallel (oneTBB), each
// with its own seed derived from options.seed and its index, so the figures do not depend on the
// thread count. quick: min(recovery_trials, 10) trials.
#include "experiments/control/control_bench_section.h"

namespace aperture::experiments {

ControlBenchSection MakeRecoverySection();

}  // namespace aperture::experiments
