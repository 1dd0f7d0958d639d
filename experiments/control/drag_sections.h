#pragma once
// The rotor-drag section of `aperture bench control` (Faessler thesis F.6, F.7; issue 4):
//
//  * "drag" (Table F.1 as the thesis ran it): first the identification of F.6, F.7.3 on each
//    trajectory: Nelder-Mead (NLopt LN_NELDERMEAD) over (d_x, d_y) of the controllers' model from
//    the drag-free model, each cost evaluation one SITL flight of two loops (quick: one) with cost
//    E_a (F.39); keys drag.identified.<trajectory>.dx, .dy [1/s], .evaluations, .E_a, and
//    drag.identified.true (the simulated vehicle's D in hover). Plot: the best coefficients per
//    evaluation (Fig. F.3). Then the circle (r 1.8 m, 4 m/s) and the Gerono lemniscate of F.7.2,
//    ten loops each (quick: one), flown without considering drag and with the D identified on the
//    circle and on the lemniscate (the six rows of Table F.1), plus the controllers' nominal D:
//    keys drag.<trajectory>.<row>.E_a, .max, .std (of |E_p|) [m] for the rows not_considered,
//    identified_on_circle, identified_on_lemniscate, nominal_model; drag.<trajectory>.E_a_off,
//    .E_a_on, .max_off, .max_on, .reduction (1 - on/off) compare not_considered with the D
//    identified on the same trajectory; drag.table_f1 the rows in cm beside the thesis'. Full runs
//    also fly the F.7 speed ramp (0 -> 5 m/s in 30 s): keys .ramp_E_a_off, .ramp_E_a_on and the
//    error over the reference speed (Figs. F.6, F.7).
// The same options.seed drives the IMU noise of every flight, so the compared flights (and the
// optimizer's cost evaluations) see the same noise and the same simulated vehicle.
#include "experiments/control/control_bench_section.h"

namespace aperture::experiments {

ControlBenchSection MakeDragSection();

}  // namespace aperture::experiments
