#pragma once
// The "recovery" section of `aperture bench control` (Faessler thesis paper B, B.3, B.4; issue 4):
// seeded random hand throws of the bench vehicle, each recovered by the on-board chain of paper B
// from simulated sensors alone: control::RecoveryPipeline (launch detection (B.29), IMU attitude
// estimator (B.22)-(B.26), height filter (B.27), (B.28) on the range sensor, five-stage state
// machine (B.3.2)) -> the simulated flight controller at 1 kHz (LQR body rates, iterative mixer,
// prioritized saturation) -> the bench vehicle (rotor drag, motor lag, default IMU noise).
//
// A throw (B.4.2: "maximum body rates above 650 deg/s, linear velocities exceeding 3.6 m/s";
// outdoors above 800 deg/s and 6 m/s): the vehicle is held still at a uniformly random attitude
// (any attitude, upside-down included) at 1.2-1.8 m for 0.4 s, then released with a horizontal
// velocity of 0-4 m/s in a random direction, a vertical velocity of -1 to +4 m/s (lobs released
// slightly downwards included) and body rates of 0-14 rad/s about a random axis. The vision pipeline is emulated: its state (ground truth in a
// shifted frame) becomes available 1 s after the height stage starts (SVO initializing during the
// horizontal drift, B.3.2).
//
// Success: no ground contact (sim::CollisionChecker, body and propellers), and a stable hover
// within kTimeLimit after the release: position stage (5) reached, then level (< 3 deg), still
// (< 0.1 m/s, < 0.2 rad/s) at the end of the flight. Keys: recovery.trials, recovery.successes,
// recovery.crashes, recovery.time_mean / time_max [s] (release -> position stage, successful
// throws), recovery.min_height [m] (lowest height of the centre over all throws). Trials run in
// parallel (oneTBB), each with its own seed derived from options.seed and its index, so the
// figures do not depend on the thread count. quick: min(recovery_trials, 10) trials.
#include "experiments/control/control_bench_section.h"

namespace aperture::experiments {

ControlBenchSection MakeRecoverySection();

}  // namespace aperture::experiments
