#pragma once
// The low-level control sections of `aperture bench control` (Faessler thesis App. G, G.6;
// issue 4). Every flight is a SITL run of the bench vehicle (control::VehicleParameters defaults:
// rotor drag d_x = 0.5, d_y = 0.35 1/s, motor lag 11 / 27 ms, kappa(f) of G.6.1) with the default
// noisy IMU (sim::ImuSensorParams, seeded from options.seed); the high-level controller flies on
// ground truth (the motion-capture setting of G.6) at 100 Hz, the flight controller runs the
// compared body-rate law / mixer / saturation at 1 kHz on the IMU gyro.
//
//  * "body_rate" (Table G.1, Figs. G.5-G.7): the low-gain P (a), high-gain P (b) and LQR (c)
//    body-rate controllers, each
//      - tracking the back-and-forth trajectory of G.6.2 (12 m/s^2, 5.7 m/s, twelve round trips;
//        quick: one): body_rate.<c>.rate_rmse = RMS of |omega_des - omega| [rad/s] at the control
//        steps, body_rate.<c>.position_rmse = E_a (F.39) [m], .pitch_rate_rmse, .x_rmse, and
//        Table G.1's statistics over every control step of the motions: .x_error_mean/_std
//        (|e_x| [m]), .thrust_angle_mean/_std (theta [rad], the angle between the thrust direction
//        the position controller demands for the true state and z_B), .pitch_rate_error_mean/_std
//        (|e_omega_y| [rad/s]); body_rate.table_g1 the rows in the thesis' units beside its values;
//      - rejecting ten upward hits on one arm during hover (quick: two), each an impulse at the
//        rotor position (linear and angular momentum change): body_rate.<c>.settling_time [s] =
//        mean (and .settling_time_std) time until the body rates stay below 0.35 rad/s and the
//        tilt below 2 deg.
//  * "mixer" (Table G.2, Fig. G.8): three minutes of hover (quick: 20 s; statistics after a 5 s
//    settle) with the iterative and with the one-shot mixer: mixer.yaw_rmse_iterative,
//    mixer.yaw_rmse_one_shot [rad] (and max), the heading error as the attitude controller
//    defines it (B.16-B.20). The vehicle's centre of mass sits 1 cm off the rotor centre in x and
//    y (a constant body torque), so hovering needs unequal thrusts, as on the thesis' real
//    vehicle. The one-shot mixer assumes one kappa; the rotors' kappa(f) varies with thrust, so
//    its yaw torque is wrong whenever the thrusts differ (G.6.3).
//  * "saturation" (G.6.4, Fig. G.9): after 3 s of hover, a simultaneous 1 m climb and 90 deg yaw
//    step with the rotor thrust range narrowed around hover as in the thesis (0.8 / 1.6 N around
//    1.25 N hover, i.e. 0.64 and 1.28 times hover thrust), the assured yaw torque of Fig. G.9
//    (eta_z,assured = 0.01 N m) and the same centre-of-mass offset, with
//    prioritized saturation (Algorithm 4) and with plain clipping: saturation.<s>.xy_max_dev [m]
//    (largest horizontal distance from the hover point at the step), saturation.<s>.crashed
//    (ground contact, boolean), saturation.<s>.yaw_settling_time [s] (|yaw - 90 deg| < 5 deg).
#include "experiments/control/control_bench_section.h"

namespace aperture::experiments {

ControlBenchSection MakeBodyRateSection();
ControlBenchSection MakeMixerSection();
ControlBenchSection MakeSaturationSection();

}  // namespace aperture::experiments
