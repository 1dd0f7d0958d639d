#pragma once
// The rotor-drag sections of `aperture bench control` (Faessler thesis F.6, F.7; issue 4):
//
//  * "drag": the circle (r 1.8 m, 4 m/s) and the Gerono lemniscate of F.7.2, each flown with the
//    position controller without and with rotor-drag compensation (F.7.4) on the bench vehicle
//    (d_x = 0.5, d_y = 0.35 1/s, motor lag, IMU noise). Keys drag.<trajectory>.E_a_off, .E_a_on
//    (F.39 over the full-speed loops, metres), .max_off, .max_on, .reduction (1 - on/off).
//    Plots: tracked vs reference x-y paths (Figs. F.4, F.5) and the error over time. Full runs
//    also fly the F.7 speed ramp (0 -> 5 m/s in 30 s): keys .ramp_E_a_off, .ramp_E_a_on and the
//    error over the reference speed (Figs. F.6, F.7).
//  * "drag_id": Nelder-Mead (NLopt LN_NELDERMEAD) over (d_x, d_y) of the controller's model,
//    each cost evaluation one SITL flight of the circle (two full-speed loops as in F.7.3),
//    minimizing E_a (F.39) (thesis F.6). Keys drag_id.true.dx, .true.dy, .estimated.dx,
//    .estimated.dy [1/s], .evaluations, .E_a_at_estimate [m]. Plot: the best coefficients per
//    evaluation (Fig. F.3).
// The same options.seed drives the IMU noise of every flight, so the compared flights (and the
// optimizer's cost evaluations) see the same noise.
#include "experiments/control/control_bench_section.h"

namespace aperture::experiments {

ControlBenchSection MakeDragSection();
ControlBenchSection MakeDragIdSection();

}  // namespace aperture::experiments
