#pragma once
// Configuration description (Serialize, config/param_archive.h) of LedHoverFlightParams, the
// `mission` section of `aperture sim led` (`--set mission.hold.integral_gain_per_s3=2`):
//
//   mission:
//     hold: {...}                 # PoseHoldParams (planning/pose_hold_params_io.h)
//     tracker: {...}              # LedTrackerParams (perception/led/led_tracker_params_io.h)
//     recovery_radius_m: 0.1      # a push is recovered within this radius ...
//     recovery_hold_s: 1.0        # ... held this long [s]
#include "experiments/led/led_hover_flight.h"
#include "perception/led/led_tracker_params_io.h"
#include "planning/pose_hold_params_io.h"

namespace aperture::experiments {

template <typename Archive>
void Serialize(Archive* a, LedHoverFlightParams* p) {
  a->Visit(APERTURE_NVP(p, hold));
  a->Visit(APERTURE_NVP(p, tracker));
  a->Visit(APERTURE_NVP(p, recovery_radius_m));
  a->Visit(APERTURE_NVP(p, recovery_hold_s));
}

}  // namespace aperture::experiments
